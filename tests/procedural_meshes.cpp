#include "tests/procedural_meshes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <vector>

#include <stdlib.h>  // mkdtemp

#include "core/attacks/remesh.hpp"
#include "core/io/write_mesh.hpp"

namespace meshmark::test {

namespace {

double mean_edge_length(const Mesh& mesh) {
  double sum = 0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) sum += (mesh.V.row(mesh.F(f, c)) - mesh.V.row(mesh.F(f, (c + 1) % 3))).norm();
  return sum / (3.0 * static_cast<double>(mesh.F.rows()));
}

}  // namespace

const Mesh& procedural_mesh(const std::string& shape) {
  static std::mutex mutex;
  static std::map<std::string, Mesh> made;
  std::lock_guard lock(mutex);
  if (auto it = made.find(shape); it != made.end()) return it->second;
  Mesh mesh;
  if (shape == "creature_small") mesh = creature(3);
  else if (shape == "creature") mesh = example_shape("creature");
  else if (shape == "creature_large") mesh = example_shape("creature-large");
  else if (shape == "creature_scan") mesh = remesh(creature(4));
  else if (shape == "creature_coarse")
    mesh = remesh(creature(4), {.target_edge_length = 1.5 * mean_edge_length(creature(4))});
  else if (shape == "torus") mesh = example_shape("torus");
  else if (shape == "torus_small") mesh = lumpy_torus(30, 16, 1);
  else if (shape == "creature_holes") mesh = example_shape("creature-holes");
  else if (shape == "pinched") mesh = pinched();
  else if (shape == "parts") mesh = example_shape("parts");
  else if (shape == "creature_inward") mesh = wound_inward(example_shape("creature"));
  else throw std::invalid_argument("no procedural mesh named '" + shape + "'");
  return made.emplace(shape, std::move(mesh)).first->second;
}

std::filesystem::path process_temp_folder(const std::string& prefix) {
  // Owns the folder: removed at exit with everything written into it.
  struct Folder {
    std::filesystem::path path;
    explicit Folder(const std::string& prefix) {
      std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
      if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot make a temporary folder");
      path = pattern;
    }
    ~Folder() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static std::mutex mutex;
  static std::map<std::string, Folder> folders;
  std::lock_guard lock(mutex);
  return folders.try_emplace(prefix, prefix).first->second.path;
}

std::filesystem::path procedural_file(const std::string& shape, const std::string& extension) {
  static std::mutex mutex;
  static const std::filesystem::path folder = process_temp_folder("meshmark-procedural");
  const Mesh& mesh = procedural_mesh(shape);
  std::lock_guard lock(mutex);
  const auto path = folder / (shape + "." + extension);
  if (!std::filesystem::exists(path)) write_mesh(path, mesh);
  return path;
}

}  // namespace meshmark::test
