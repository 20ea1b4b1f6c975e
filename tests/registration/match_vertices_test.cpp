// Registration by the vertices a copy kept, on an unevenly tessellated ball (its shape fits every
// turn): a moved, reordered, noisy or cut copy is put back where it was; nothing is ever put
// anywhere else.

#include "core/registration/match_vertices.hpp"

#include <gtest/gtest.h>

#include "core/attacks/add_noise.hpp"
#include "core/attacks/crop.hpp"
#include "core/attacks/remesh.hpp"
#include "core/attacks/reorder.hpp"
#include "core/attacks/similarity_transform.hpp"
#include "core/mesh/example_shapes.hpp"

namespace meshmark {
namespace {

const Mesh& ball() {
  static const Mesh mesh = uneven_ball(3);
  return mesh;
}

const VertexSignatures& ball_signatures() {
  static const VertexSignatures signatures(ball().V, 1);
  return signatures;
}

double diagonal() { return (ball().V.colwise().maxCoeff() - ball().V.colwise().minCoeff()).norm(); }

// The largest distance, in diagonals, between the original's vertices and the moved copy's
// mapped back by `back`.
double max_error(const Mesh& moved_in_order, const Similarity& back) {
  return (back.apply_to_rows(moved_in_order.V) - ball().V).rowwise().norm().maxCoeff() / diagonal();
}

TEST(MatchVertices, PutsAMovedReorderedCopyBackExactly) {
  for (const std::uint64_t seed : {1, 2, 3}) {
    const Mesh moved = transform_mesh(ball(), random_similarity(ball(), seed));
    const auto back = match_vertices(reorder(moved, seed), ball_signatures(), diagonal()).poses;
    ASSERT_FALSE(back.empty()) << "seed " << seed;
    EXPECT_LT(max_error(moved, back.front()), 1e-9) << "seed " << seed;
  }
}

TEST(MatchVertices, FollowsACopyWhoseVerticesMovedAsMuchAsAMark) {
  const Mesh moved = transform_mesh(ball(), random_similarity(ball(), 4));
  const Mesh noisy = add_noise(moved, 0.1, NoiseReference::bbox_diagonal, 4);  // ±0.1 % of the diagonal per coordinate
  const auto back = match_vertices(noisy, ball_signatures(), diagonal()).poses;
  ASSERT_FALSE(back.empty());
  EXPECT_LT(max_error(moved, back.front()), 2e-3);
}

TEST(MatchVertices, PutsBackTheHalfOfACopyThatWasKept) {
  const Mesh moved = transform_mesh(ball(), random_similarity(ball(), 5));
  const auto back = match_vertices(crop(moved, 0.5, 5), ball_signatures(), diagonal()).poses;
  ASSERT_FALSE(back.empty());
  EXPECT_LT(max_error(moved, back.front()), 1e-9);
}

// A remeshed ball keeps many vertices within the tolerance of where they were: matched, it is put
// back right; never anywhere else.
TEST(MatchVertices, PutsARemeshedCopyBackRightOrNowhere) {
  const Similarity T = random_similarity(ball(), 7);
  const Eigen::Vector3d probe(0.3, -0.7, 0.2);
  for (const Similarity& back : match_vertices(remesh(transform_mesh(ball(), T)), ball_signatures(), diagonal()).poses)
    EXPECT_LT((back.apply(T.apply(probe)) - probe).norm() / diagonal(), 0.01);
}

TEST(MatchVertices, MatchesNothingOfAnotherShape) {
  const Mesh other = creature(3);
  EXPECT_TRUE(
      match_vertices(transform_mesh(other, random_similarity(other, 8)), ball_signatures(), diagonal()).poses.empty());
}

// An original holding one part twice: a copy of that part fits either place, and both poses are
// candidates (only the mark tells which part it was).
TEST(MatchVertices, ACopyOfAPartTheOriginalRepeatsGetsBothPoses) {
  const Mesh twins = side_by_side(ball(), ball());
  const VertexSignatures signatures(twins.V, 1);
  const double twins_diagonal = (twins.V.colwise().maxCoeff() - twins.V.colwise().minCoeff()).norm();
  const Similarity T = random_similarity(ball(), 9);
  const auto poses = match_vertices(transform_mesh(ball(), T), signatures, twins_diagonal).poses;
  ASSERT_EQ(poses.size(), 2u);
  const Eigen::Vector3d offset = twins.V.row(ball().V.rows()) - twins.V.row(0);  // where the second ball sits
  std::vector<double> shifts;
  for (const Similarity& back : poses)
    shifts.push_back(
        (back.apply(T.apply(ball().V.row(0).transpose())) - Eigen::Vector3d(ball().V.row(0).transpose())).norm());
  std::sort(shifts.begin(), shifts.end());
  EXPECT_LT(shifts[0] / twins_diagonal, 1e-9);
  EXPECT_NEAR(shifts[1], offset.norm(), 1e-9 * twins_diagonal);
}

// A copy that is mostly a regular tessellation (a torus's: each vertex's signature is shared by a
// whole ring), moved as much as a mark moves it: the torus's matches are any of their ring and
// drown the ball's, whose distinctive matches alone put the copy back.
TEST(MatchVertices, ACopyMostlyOfARegularTessellationIsPutBackByItsFewDistinctVertices) {
  const Mesh original = side_by_side(torus(240, 24), uneven_ball(2));
  const VertexSignatures signatures(original.V, 1);
  const double original_diagonal = (original.V.colwise().maxCoeff() - original.V.colwise().minCoeff()).norm();
  const Mesh moved = transform_mesh(original, random_similarity(original, 11));
  const Mesh marked = add_noise(moved, 0.05, NoiseReference::bbox_diagonal, 11);
  const VertexPoses back = match_vertices(marked, signatures, original_diagonal);
  EXPECT_TRUE(back.distinctive) << "every match together found a pose";
  ASSERT_FALSE(back.poses.empty());
  EXPECT_LT((back.poses.front().apply_to_rows(moved.V) - original.V).rowwise().norm().maxCoeff() / original_diagonal,
            2e-3);
}

TEST(MatchVertices, SignaturesIgnoreRepeatedPositionsAndScale) {
  Mesh twice = ball();
  twice.V.conservativeResize(2 * ball().V.rows(), 3);
  twice.V.bottomRows(ball().V.rows()) = ball().V;  // every vertex stored twice, as split exports do
  Vertices distinct, distinct_scaled;
  const Eigen::MatrixXd doubled = neighbour_signatures(twice.V, distinct, 1);
  EXPECT_EQ(distinct.rows(), ball().V.rows());
  const Eigen::MatrixXd scaled = neighbour_signatures(Vertices(3.5 * ball().V), distinct_scaled, 1);
  EXPECT_LT((doubled - scaled).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_GT(doubled.col(0).minCoeff(), 0) << "a vertex found its own copy as a neighbour";
}

}  // namespace
}  // namespace meshmark
