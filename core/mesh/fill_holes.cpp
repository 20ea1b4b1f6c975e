#include "core/mesh/fill_holes.hpp"

#include <map>
#include <vector>

namespace meshmark {

FilledHoles fill_holes(const Mesh& mesh) {
  FilledHoles out;
  out.original_vertices = mesh.V.rows();
  out.original_faces = mesh.F.rows();
  // Boundary half-edges: a face's a→b whose reverse no face has; each boundary vertex starts one.
  std::map<std::pair<int, int>, int> half_edges;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++half_edges[{mesh.F(f, k), mesh.F(f, (k + 1) % 3)}];
  std::map<int, int> next;  // boundary vertex → the next along its loop
  for (const auto& [edge, count] : half_edges)
    if (!half_edges.count({edge.second, edge.first})) next[edge.first] = edge.second;
  std::vector<double> coords(mesh.V.data(), mesh.V.data() + mesh.V.size());
  std::vector<int> faces(mesh.F.data(), mesh.F.data() + mesh.F.size());
  std::map<int, char> visited;
  for (const auto& [start, ignored] : next) {
    if (visited[start]) continue;
    std::vector<int> loop;
    for (int v = start; !visited[v]; v = next.at(v)) {
      visited[v] = 1;
      loop.push_back(v);
      if (!next.count(v)) break;
    }
    if (loop.size() < 3) continue;
    // Centroid and Newell normal of the loop; the filling's faces run against the loop, so its
    // outside is along −normal.
    Eigen::Vector3d centre = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Eigen::Vector3d a = mesh.V.row(loop[i]), b = mesh.V.row(loop[(i + 1) % loop.size()]);
      centre += a;
      normal += a.cross(b);
    }
    centre /= static_cast<double>(loop.size());
    double radius = 0;
    for (const int v : loop) radius += (mesh.V.row(v).transpose() - centre).norm();
    radius /= static_cast<double>(loop.size());
    if (normal.norm() > 0) centre -= 0.25 * radius * normal.normalized();
    const int c = static_cast<int>(coords.size() / 3);
    coords.insert(coords.end(), {centre.x(), centre.y(), centre.z()});
    for (std::size_t i = 0; i < loop.size(); ++i) faces.insert(faces.end(), {loop[(i + 1) % loop.size()], loop[i], c});
    ++out.holes;
  }
  out.mesh.V = Eigen::Map<const Vertices>(coords.data(), static_cast<Eigen::Index>(coords.size() / 3), 3);
  out.mesh.F = Eigen::Map<const Faces>(faces.data(), static_cast<Eigen::Index>(faces.size() / 3), 3);
  return out;
}

}  // namespace meshmark
