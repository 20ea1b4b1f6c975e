#include "core/mesh/edge_incidence.hpp"

#include <gtest/gtest.h>

#include <map>
#include <utility>

#include "tests/test_data.hpp"

namespace meshmark {
namespace {

// The incidence counted the slow, obvious way: a map from each undirected edge to its uses.
struct Uses {
  int faces = 0, along = 0;
};
std::map<std::pair<int, int>, Uses> count_uses(const Faces& F) {
  std::map<std::pair<int, int>, Uses> uses;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      Uses& u = uses[{std::min(a, b), std::max(a, b)}];
      ++u.faces;
      u.along += a < b ? 1 : 0;
    }
  return uses;
}

void expect_incidence_of(const Faces& F) {
  const EdgeIncidence inc = edge_incidence(F);
  const auto uses = count_uses(F);
  ASSERT_EQ(static_cast<std::size_t>(inc.edges.rows()), uses.size());
  std::size_t e = 0;
  for (const auto& [edge, use] : uses) {  // the map's order is lexicographic, as promised
    EXPECT_EQ(inc.edges(static_cast<Eigen::Index>(e), 0), edge.first);
    EXPECT_EQ(inc.edges(static_cast<Eigen::Index>(e), 1), edge.second);
    EXPECT_EQ(inc.face_count[e], use.faces);
    EXPECT_EQ(inc.along_count[e], use.along);
    ++e;
  }
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3), edge = inc.face_edges(f, k);
      EXPECT_EQ(inc.edges(edge, 0), std::min(a, b));
      EXPECT_EQ(inc.edges(edge, 1), std::max(a, b));
    }
}

TEST(EdgeIncidence, CountsEveryEdgesFacesAndDirectionsOnAClosedSurface) {
  expect_incidence_of(test::procedural_mesh("creature").F);
}

TEST(EdgeIncidence, CountsBoundaryAndNonManifoldEdgesOfASoup) {
  Faces soup(5, 3);
  soup << 0, 1, 2,  // three faces on edge 0–1, one of them the other way round
      1, 0, 3,      //
      0, 1, 4,      //
      2, 1, 5,      //
      7, 6, 5;      // an island far along the index range
  expect_incidence_of(soup);
  const EdgeIncidence inc = edge_incidence(soup);
  EXPECT_EQ(inc.face_count[0], 3);   // 0–1
  EXPECT_EQ(inc.along_count[0], 2);  // 0→1 twice, 1→0 once
}

TEST(EdgeIncidence, IndicesFarBeyondTheFaceCountGiveTheSameIncidenceShifted) {
  // Far-off indices take the comparison sort instead of the buckets: the answer must not change.
  const Faces& F = test::procedural_mesh("creature").F;
  const int offset = 1 << 28;
  const EdgeIncidence near = edge_incidence(F);
  const EdgeIncidence far = edge_incidence((F.array() + offset).matrix());
  EXPECT_TRUE((far.edges.array() - offset).matrix() == near.edges);
  EXPECT_EQ(far.face_count, near.face_count);
  EXPECT_EQ(far.along_count, near.along_count);
  EXPECT_TRUE(far.face_edges == near.face_edges);
}

TEST(EdgeIncidence, NoFacesNoEdges) {
  const EdgeIncidence inc = edge_incidence(Faces(0, 3));
  EXPECT_EQ(inc.edges.rows(), 0);
  EXPECT_EQ(inc.face_edges.rows(), 0);
}

}  // namespace
}  // namespace meshmark
