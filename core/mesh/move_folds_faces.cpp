#include "core/mesh/move_folds_faces.hpp"

#include <Eigen/Geometry>

namespace meshmark {

bool move_folds_faces(const HalfedgeMesh& mesh, HalfedgeMesh::VertexHandle v, HalfedgeMesh::VertexHandle other,
                      const Eigen::Vector3d& at, double min_cosine) {
  for (const auto f : mesh.vf_range(v)) {
    Eigen::Vector3d p[3], q[3];
    int k = 0;
    bool on_edge = false;
    for (const auto u : mesh.fv_range(f)) {
      on_edge = on_edge || u == other;
      const auto& point = mesh.point(u);
      p[k] = Eigen::Vector3d(point[0], point[1], point[2]);
      q[k] = u == v ? at : p[k];
      ++k;
    }
    if (on_edge) continue;  // these faces disappear with the collapse
    const Eigen::Vector3d before = (p[1] - p[0]).cross(p[2] - p[0]), after = (q[1] - q[0]).cross(q[2] - q[0]);
    if (before.dot(after) <= min_cosine * before.norm() * after.norm()) return true;
  }
  return false;
}

}  // namespace meshmark
