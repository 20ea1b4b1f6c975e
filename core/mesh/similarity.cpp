#include "core/mesh/similarity.hpp"

#include <Eigen/Geometry>

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

Similarity fit_similarity(const Eigen::Matrix3Xd& from, const Eigen::Matrix3Xd& to) {
  const Eigen::Matrix4d m = Eigen::umeyama(from, to, true);
  Similarity T;
  T.scale = m.block<3, 1>(0, 0).norm();
  T.R = m.block<3, 3>(0, 0) / T.scale;
  T.t = m.block<3, 1>(0, 3);
  return T;
}

}  // namespace meshmark
