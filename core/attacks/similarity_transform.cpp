#include "core/attacks/similarity_transform.hpp"

#include <cmath>
#include <string>

#include "core/util/keyed_random.hpp"

namespace meshmark {

Similarity random_similarity(const Mesh& mesh, std::uint64_t seed) {
  KeyedRandom random("attack", "similarity/" + std::to_string(seed));
  // A uniform rotation from a uniform unit quaternion (Shoemake).
  const double u1 = random.unit(), u2 = 2 * M_PI * random.unit(), u3 = 2 * M_PI * random.unit();
  const Eigen::Quaterniond q(std::sqrt(u1) * std::cos(u3), std::sqrt(1 - u1) * std::sin(u2),
                             std::sqrt(1 - u1) * std::cos(u2), std::sqrt(u1) * std::sin(u3));
  Similarity T;
  T.R = q.normalized().toRotationMatrix();
  T.scale = std::exp2(2 * random.unit() - 1);
  const double diagonal = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
  T.t =
      diagonal * Eigen::Vector3d(2 * random.unit() - 1, 2 * random.unit() - 1, 2 * random.unit() - 1) / std::sqrt(3.0);
  return T;
}

Mesh transform_mesh(const Mesh& mesh, const Similarity& transform) { return {transform.apply_to_rows(mesh.V), mesh.F}; }

Mesh mirror_mesh(const Mesh& mesh, int axis, std::uint64_t seed) {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  if (axis >= 0) {
    normal[axis] = 1;
  } else {
    KeyedRandom random("attack", "mirror/" + std::to_string(seed));
    const double z = 2 * random.unit() - 1, turn = 2 * M_PI * random.unit();  // uniform on the sphere
    normal = Eigen::Vector3d(std::sqrt(1 - z * z) * std::cos(turn), std::sqrt(1 - z * z) * std::sin(turn), z);
  }
  if (mesh.V.rows() == 0) return mesh;
  const Eigen::RowVector3d centre = mesh.V.colwise().mean();  // on the plane: mirrored again, the same
  const Eigen::Matrix3d reflection = Eigen::Matrix3d::Identity() - 2 * normal * normal.transpose();
  Mesh mirrored{((mesh.V.rowwise() - centre) * reflection).rowwise() + centre, mesh.F};
  mirrored.F.col(1).swap(mirrored.F.col(2));
  return mirrored;
}

}  // namespace meshmark
