// The two readings of a suspect's offset: at the original's own vertices, and by projection.

#include "core/watermark/read_suspect.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/attacks/reorder.hpp"
#include "core/attacks/similarity_transform.hpp"
#include "core/mesh/mesh.hpp"
#include "core/watermark/nuisance_fields.hpp"
#include "core/watermark/watermark.hpp"
#include "tests/procedural_meshes.hpp"

namespace meshmark {
namespace {

const PreparedModel& prepared_creature() {
  static const PreparedModel m = prepare_model(test::procedural_mesh("creature_large"));
  return m;
}

// A smooth bump along the normals, a few ten-thousandths of the diagonal: what a mark looks like.
Mesh bumped() {
  Mesh copy = prepared_creature().mesh;
  for (Eigen::Index v = 0; v < copy.V.rows(); ++v)
    copy.V.row(v) +=
        4e-4 * prepared_creature().diagonal * std::sin(5.0 * copy.V(v, 0)) * prepared_creature().normals.row(v);
  return copy;
}

// A copy on the original's vertices, reordered and moved, reads at those vertices as the copy in
// place does: the same normal offsets, the same nuisance fields taken out (the pairs' similarity,
// taken out first, moves the reading by a ten-thousandth of the mark at most).
TEST(ReadSuspect, AReorderedMovedCopyReadsAtItsVerticesAsInPlace) {
  const Mesh copy = bumped();
  const Mesh reordered = reorder(copy, 7);  // as registration leaves it: in place, in its own order
  const Mesh moved = transform_mesh(reordered, random_similarity(reordered, 11));
  const auto offsets =
      corresponding_offsets(prepared_creature().mesh, reordered, moved.V, median_edge_length(prepared_creature().mesh));
  ASSERT_TRUE(offsets);
  const Displacement d = read_at_vertices(prepared_creature(), *offsets, {}, 1);
  EXPECT_EQ(d.missing, 0u);
  Eigen::VectorXd in_place =
      (copy.V - prepared_creature().mesh.V).cwiseProduct(prepared_creature().normals).rowwise().sum();
  remove_fit(in_place, d.found, nuisance_fields(prepared_creature(), 1));
  EXPECT_GT(in_place.cwiseAbs().maxCoeff(), 1e-4 * prepared_creature().diagonal);
  EXPECT_LT((d.t - in_place).cwiseAbs().maxCoeff(), 1e-3 * in_place.cwiseAbs().maxCoeff());
}

// Where both apply, the vertex reading and the projection agree to within what projection's
// sampling interpolates.
TEST(ReadSuspect, TheVertexReadingAgreesWithProjection) {
  const Mesh copy = bumped();
  const RegistrationTarget target(prepared_creature().outward_mesh());
  const Displacement projected = read_suspect(prepared_creature(), target, copy, {}, 1);
  const auto offsets =
      corresponding_offsets(prepared_creature().mesh, copy, copy.V, median_edge_length(prepared_creature().mesh));
  ASSERT_TRUE(offsets);
  const Displacement at_vertices = read_at_vertices(prepared_creature(), *offsets, {}, 1);
  const double correlation = projected.t.normalized().dot(at_vertices.t.normalized());
  EXPECT_GT(correlation, 0.9);
}

}  // namespace
}  // namespace meshmark
