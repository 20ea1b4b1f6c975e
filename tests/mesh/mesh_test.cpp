// The mesh type's one predicate: whether two meshes share their vertices' places and faces.

#include "core/mesh/mesh.hpp"

#include <gtest/gtest.h>

namespace meshmark {
namespace {

Mesh two_triangles() {
  Mesh m{Vertices(4, 3), Faces(2, 3)};
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0;
  m.F << 0, 1, 2, 2, 1, 3;
  return m;
}

// Moved vertices keep the connectivity; a face more, a face renumbered or a vertex more do not,
// and a copy with more faces than the original is told apart without reading past the original's
// (the sanitizer run would stop on it).
TEST(Mesh, SameConnectivityComparesCountsBeforeFaces) {
  const Mesh original = two_triangles();
  Mesh moved = original;
  moved.V.array() += 3;
  EXPECT_TRUE(same_connectivity(moved, original));
  Mesh more_faces = original;
  more_faces.F.conservativeResize(3, 3);
  more_faces.F.row(2) << 0, 2, 3;
  EXPECT_FALSE(same_connectivity(more_faces, original));
  EXPECT_FALSE(same_connectivity(original, more_faces));
  Mesh renumbered = original;
  renumbered.F.row(1) << 1, 3, 2;
  EXPECT_FALSE(same_connectivity(renumbered, original));
  Mesh more_vertices = original;
  more_vertices.V.conservativeResize(5, 3);
  more_vertices.V.row(4).setZero();
  EXPECT_FALSE(same_connectivity(more_vertices, original));
}

}  // namespace
}  // namespace meshmark
