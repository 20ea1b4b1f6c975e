#include "core/attacks/split_vertices.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "core/util/keyed_random.hpp"

namespace meshmark {

Mesh split_vertices(const Mesh& mesh, double fraction, std::uint64_t seed) {
  if (!(fraction >= 0 && fraction <= 1)) throw std::invalid_argument("the share of split vertices must be in [0, 1]");
  KeyedRandom random("attack", "split/" + std::to_string(seed));
  std::vector<char> split(static_cast<std::size_t>(mesh.V.rows()));
  for (char& s : split) s = random.unit() < fraction;
  // Kept vertices first, in their order; then one copy of a split vertex per face corner.
  std::vector<int> kept(split.size(), -1);
  std::vector<double> coords;
  for (std::size_t v = 0; v < split.size(); ++v)
    if (!split[v]) {
      kept[v] = static_cast<int>(coords.size() / 3);
      coords.insert(coords.end(), {mesh.V(static_cast<Eigen::Index>(v), 0), mesh.V(static_cast<Eigen::Index>(v), 1),
                                   mesh.V(static_cast<Eigen::Index>(v), 2)});
    }
  Mesh out;
  out.F = mesh.F;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.F(f, k);
      if (!split[static_cast<std::size_t>(v)]) {
        out.F(f, k) = kept[static_cast<std::size_t>(v)];
        continue;
      }
      out.F(f, k) = static_cast<int>(coords.size() / 3);  // this corner's own copy
      coords.insert(coords.end(), {mesh.V(v, 0), mesh.V(v, 1), mesh.V(v, 2)});
    }
  out.V = Eigen::Map<const Vertices>(coords.data(), static_cast<Eigen::Index>(coords.size() / 3), 3);
  return out;
}

}  // namespace meshmark
