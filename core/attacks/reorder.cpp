#include "core/attacks/reorder.hpp"

#include <numeric>
#include <string>
#include <vector>

#include "core/util/keyed_random.hpp"

namespace meshmark {

Mesh reorder(const Mesh& mesh, std::uint64_t seed) {
  KeyedRandom random("attack", "reorder/" + std::to_string(seed));
  std::vector<int> vertex_order(static_cast<std::size_t>(mesh.V.rows())),
      face_order(static_cast<std::size_t>(mesh.F.rows()));
  std::iota(vertex_order.begin(), vertex_order.end(), 0);
  std::iota(face_order.begin(), face_order.end(), 0);
  random.shuffle(vertex_order);
  random.shuffle(face_order);
  std::vector<int> new_index(vertex_order.size());
  Mesh out;
  out.V.resize(mesh.V.rows(), 3);
  for (std::size_t i = 0; i < vertex_order.size(); ++i) {
    out.V.row(static_cast<Eigen::Index>(i)) = mesh.V.row(vertex_order[i]);
    new_index[vertex_order[i]] = static_cast<int>(i);
  }
  out.F.resize(mesh.F.rows(), 3);
  for (std::size_t i = 0; i < face_order.size(); ++i) {
    const int shift = static_cast<int>(random.below(3));
    for (int k = 0; k < 3; ++k)
      out.F(static_cast<Eigen::Index>(i), k) = new_index[mesh.F(face_order[i], (k + shift) % 3)];
  }
  return out;
}

}  // namespace meshmark
