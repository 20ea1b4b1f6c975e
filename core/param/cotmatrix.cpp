#include "core/param/cotmatrix.hpp"

#include <algorithm>
#include <vector>

#include "core/mesh/edge_incidence.hpp"

namespace meshmark {

Eigen::SparseMatrix<double> cotmatrix(const Vertices& V, const Faces& F, const CotmatrixOptions& options) {
  const EdgeIncidence inc = edge_incidence(F);
  std::vector<double> weight(inc.face_count.size(), 0.0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      // The angle at corner k is opposite the edge from corner k+1 to corner k+2.
      const Eigen::Vector3d p = V.row(F(f, k));
      const Eigen::Vector3d u = V.row(F(f, (k + 1) % 3)) - p.transpose(), w = V.row(F(f, (k + 2) % 3)) - p.transpose();
      const double cross = u.cross(w).norm();
      const double cot = cross > 0 ? u.dot(w) / cross : options.max_weight;
      weight[inc.face_edges(f, (k + 1) % 3)] += 0.5 * cot;
    }
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(4 * weight.size());
  for (std::size_t e = 0; e < weight.size(); ++e) {
    const double w = std::clamp(weight[e], options.min_weight, options.max_weight);
    const int a = inc.edges(e, 0), b = inc.edges(e, 1);
    triplets.emplace_back(a, b, -w);
    triplets.emplace_back(b, a, -w);
    triplets.emplace_back(a, a, w);
    triplets.emplace_back(b, b, w);
  }
  Eigen::SparseMatrix<double> L(V.rows(), V.rows());
  L.setFromTriplets(triplets.begin(), triplets.end());
  return L;
}

}  // namespace meshmark
