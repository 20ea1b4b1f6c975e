#pragma once
// Subdivision attacks: every face split, the surface refined (and, for Loop and √3, smoothed).

#include <string>

#include "core/mesh/mesh.hpp"

namespace meshmark {

enum class SubdivisionScheme {
  midpoint,  ///< 1-to-4 with new vertices at edge midpoints: the surface is unchanged
  loop,      ///< Loop (1987): 1-to-4 and smoothing towards a C² limit surface
  sqrt3,     ///< Kobbelt's √3: 1-to-3 and an edge flip, smoothing
};
std::string to_string(SubdivisionScheme scheme);
/// "midpoint", "loop", "sqrt3"; throws std::invalid_argument.
SubdivisionScheme parse_subdivision_scheme(const std::string& name);

/// The mesh subdivided `steps` times. The original vertices keep their indices (first #V rows);
/// for Loop and √3 they move. Needs a manifold mesh (throws std::invalid_argument otherwise).
Mesh subdivide(const Mesh& mesh, SubdivisionScheme scheme, int steps = 1);

}  // namespace meshmark
