#pragma once
// One surface out of stored vertices: those at exactly the same position are one vertex, so that
// seams (a vertex stored once per texture coordinate or normal, as every glTF has), flat-shaded
// exports and primitives sharing positions form one surface for validation, parameterization and
// embedding; every copy then moves together and seams stay closed.

#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct WeldedSurface {
  /// Welded vertices, numbered in order of first appearance among the stored vertices a
  /// triangle uses; triangles over them, without those welding collapsed (two corners at one
  /// position).
  Mesh mesh;
  std::vector<int> vertex_of;  ///< per stored vertex: its surface vertex, −1 when no triangle uses it
  std::vector<int> face_of;    ///< per surface triangle: the stored triangle it came from
  std::size_t collapsed_triangles = 0;
  /// Triangles over the same three surface vertices as an earlier one, whatever their winding (the
  /// back of a double-sided sheet, a face stored twice): left out, so that one surface carries the
  /// mark and both sides, welded, move with it.
  std::size_t duplicate_triangles = 0;
  std::size_t welded_copies = 0;  ///< stored vertices that joined an earlier one at the same position
};

/// Welds by exact position (−0 and +0 alike). O(n) expected (hashing), O(n log n) whatever the
/// positions (sorting, when they collide).
/// `V` may map memory held elsewhere (a triangle soup as read).
WeldedSurface weld_positions(const Eigen::Ref<const Vertices>& V, const Faces& F);

/// A mesh known to be welded already (distinct positions, every vertex on a triangle, none
/// collapsed or repeated), as weld_positions would give it back, without the work.
WeldedSurface already_welded(Mesh mesh);

/// Stored positions after the surface moved to `surface_V`: every used stored vertex at its
/// surface vertex's new position, unused ones where they were. `stored_V` may be the first rows
/// of what was welded (a scene's slots, before its further instances).
Vertices stored_positions(const WeldedSurface& surface, const Vertices& surface_V, const Vertices& stored_V);

}  // namespace meshmark
