#pragma once
// Where registration starts: the principal axes of the suspect's samples mapped onto the
// original's with every sign and order, turns the axes cannot tell apart, and starts at the scale
// of the vertex spacing slid to either end of the original. Internal to core/registration.

#include <string>
#include <utility>
#include <vector>

#include "core/mesh/mesh.hpp"
#include "core/mesh/similarity.hpp"
#include "core/registration/align_meshes.hpp"

namespace meshmark::registration {

struct Moments {
  Eigen::Vector3d centroid;
  Eigen::Matrix3d axes;
  Eigen::Vector3d variances;  // along `axes`, decreasing
  double spread;
};

Moments principal_moments(const Vertices& P);

using NamedStarts = std::vector<std::pair<Similarity, std::string>>;

/// Turns about the original's centroid that its principal axes cannot tell apart: about an axis
/// whose two companions have about the same variance (a bottle, a wheel), or any turn when all
/// three have (a ball). Empty when the axes are distinct.
std::vector<Eigen::Matrix3d> ambiguous_turns(const Eigen::Vector3d& variances, const Eigen::Matrix3d& axes);

/// Turns by 30° steps about each of the original's principal axes, where a part of the shape its
/// axes do not see (a rock under a round tower) fixes the turn and a cut copy's axes moved with the
/// cut; by 15° about the axis whose companions' variances are the most alike, the shape's nearest
/// to a symmetry, where a pattern repeated around it (a tower's windows, 22.5° apart) catches ICP
/// started half a step away in its next repeat. With the axis-ordered starts' 180° turns, they
/// reach every step.
std::vector<Eigen::Matrix3d> turns_about_axes(const Eigen::Vector3d& variances, const Eigen::Matrix3d& axes);

/// The starts: the identity, the 24 rotations mapping the suspect's principal axes onto the
/// original's, and those turned by every ambiguous_turns (and, for a search again, by
/// turns_about_axes too).
NamedStarts starting_poses(const Moments& m, const RegistrationTarget& target, bool turn_about_every_axis);

/// The median over vertices of the shortest edge each has: a copy that kept the original's
/// vertices, however cut, keeps their spacing, so the ratio of two spacings is its scale where the
/// spread of a cut copy is not. 0 for a mesh without edges.
double vertex_spacing(const Mesh& mesh);

/// The scale that matches the suspect's vertex spacing to the original's; 0 when either has none.
double spacing_scale(const Mesh& suspect, const RegistrationTarget& target);

/// The four axis-ordered starts of starting_poses (after the identity) at the scale of the vertex
/// spacing, each about the centroids and at either end; none when the spacing says nothing.
NamedStarts spacing_starts(const NamedStarts& shape_starts, const Moments& m, const Vertices& points, double scale,
                           const RegistrationTarget& target);

}  // namespace meshmark::registration
