#include "core/mesh/normal_rotations.hpp"

#include "core/mesh/vertex_normals.hpp"

namespace meshmark {

std::vector<Eigen::Quaterniond> normal_rotations(const Vertices& V, const Vertices& V2, const Faces& F) {
  const Vertices before = vertex_normals(V, F), after = vertex_normals(V2, F);
  std::vector<Eigen::Quaterniond> r(static_cast<std::size_t>(V.rows()), Eigen::Quaterniond::Identity());
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    const Eigen::Vector3d a = before.row(v).transpose(), b = after.row(v).transpose();
    if (a.squaredNorm() == 0 || b.squaredNorm() == 0 || a == b) continue;
    r[static_cast<std::size_t>(v)] = Eigen::Quaterniond::FromTwoVectors(a, b);
  }
  return r;
}

Eigen::Vector3d rotate_shared(const Eigen::Vector3d& n, const std::vector<const Eigen::Quaterniond*>& r) {
  bool all_identity = true;
  for (const auto* q : r) all_identity = all_identity && q->w() == 1.0;
  if (r.empty() || all_identity) return n;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto* q : r) sum += *q * n;
  const double length = sum.norm();
  return length > 0 ? Eigen::Vector3d(sum * (n.norm() / length)) : n;
}

}  // namespace meshmark
