#include "core/mesh/similarity.hpp"

namespace meshmark {

Vertices Similarity::apply_to_rows(const Vertices& V) const {
  Vertices out(V.rows(), 3);
  for (Eigen::Index i = 0; i < V.rows(); ++i) out.row(i) = apply(Eigen::Vector3d(V.row(i).transpose())).transpose();
  return out;
}

Similarity Similarity::inverse() const {
  Similarity inv;
  inv.R = R.transpose();
  inv.scale = 1.0 / scale;
  inv.t = -inv.scale * (inv.R * t);
  return inv;
}

}  // namespace meshmark
