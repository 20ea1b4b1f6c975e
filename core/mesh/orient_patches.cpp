#include "core/mesh/orient_patches.hpp"

#include <vector>

#include "core/mesh/edge_incidence.hpp"
#include "core/mesh/orientation.hpp"

namespace meshmark {

OrientedPatches orient_patches(const Vertices& V, const Faces& F) {
  const EdgeIncidence inc = edge_incidence(F);
  const auto faces = static_cast<std::size_t>(F.rows());
  // The (at most two) faces of each manifold edge.
  std::vector<int> first(static_cast<std::size_t>(inc.edges.rows()), -1), second(first.size(), -1);
  for (std::size_t f = 0; f < faces; ++f)
    for (int k = 0; k < 3; ++k) {
      const auto e = static_cast<std::size_t>(inc.face_edges(static_cast<Eigen::Index>(f), k));
      (first[e] < 0 ? first[e] : second[e]) = static_cast<int>(f);
    }
  // Does face f traverse its corner-k edge from the smaller vertex to the larger?
  const auto along = [&](std::size_t f, int k) {
    return F(static_cast<Eigen::Index>(f), k) < F(static_cast<Eigen::Index>(f), (k + 1) % 3);
  };
  OrientedPatches out;
  out.faces = F;
  std::vector<int> patch(faces, -1);
  std::vector<char> flip(faces, 0);
  std::vector<std::size_t> stack;
  for (std::size_t seed = 0; seed < faces; ++seed) {
    if (patch[seed] >= 0) continue;
    const int id = static_cast<int>(out.patches++);
    std::vector<std::size_t> members;
    patch[seed] = id;
    stack.push_back(seed);
    bool closed = true;
    while (!stack.empty()) {
      const std::size_t f = stack.back();
      stack.pop_back();
      members.push_back(f);
      for (int k = 0; k < 3; ++k) {
        const auto e = static_cast<std::size_t>(inc.face_edges(static_cast<Eigen::Index>(f), k));
        if (inc.face_count[e] != 2) {
          closed = false;
          continue;
        }
        const std::size_t g = static_cast<std::size_t>(first[e] == static_cast<int>(f) ? second[e] : first[e]);
        if (patch[g] >= 0) continue;
        int kg = 0;
        while (inc.face_edges(static_cast<Eigen::Index>(g), kg) != static_cast<int>(e)) ++kg;
        // Consistent neighbours traverse their shared edge in opposite directions.
        const bool same_direction = along(f, k) == along(g, kg);
        flip[g] = static_cast<char>(flip[f] ^ same_direction);
        patch[g] = id;
        stack.push_back(g);
      }
    }
    std::size_t flipped = 0;
    for (const std::size_t f : members) flipped += flip[f];
    bool reverse_all = 2 * flipped > members.size();
    if (closed) {
      Faces patch_faces(static_cast<Eigen::Index>(members.size()), 3);
      for (std::size_t i = 0; i < members.size(); ++i) {
        patch_faces.row(static_cast<Eigen::Index>(i)) = F.row(static_cast<Eigen::Index>(members[i]));
        if (flip[members[i]])
          std::swap(patch_faces(static_cast<Eigen::Index>(i), 1), patch_faces(static_cast<Eigen::Index>(i), 2));
      }
      reverse_all = signed_volume(V, patch_faces) < 0;
    }
    for (const std::size_t f : members) {
      if (static_cast<bool>(flip[f]) != reverse_all) {
        std::swap(out.faces(static_cast<Eigen::Index>(f), 1), out.faces(static_cast<Eigen::Index>(f), 2));
        ++out.reversed;
      }
    }
  }
  return out;
}

}  // namespace meshmark
