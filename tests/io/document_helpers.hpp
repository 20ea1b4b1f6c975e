#pragma once
// What the document tests share: moving every slot a little, and reading written files back.

#include <filesystem>
#include <memory>
#include <cstring>
#include <nlohmann/json.hpp>
#include <random>
#include <utility>

#include "core/io/mesh_document.hpp"

namespace meshmark::test {

// Reads a written document back: the main file from `files`, companions from `files` first, then
// from the original folder.
inline std::unique_ptr<MeshDocument> read_written(const DocumentFiles& files, const std::filesystem::path& original) {
  DocumentReadOptions options;
  const std::filesystem::path folder = original.parent_path();
  options.companion = [&files, folder](const std::string& uri) {
    if (auto it = files.find(uri); it != files.end()) return it->second;
    return read_file_bytes(folder / uri, 1u << 30);
  };
  return read_document(files.at(""), mesh_format_from_path(original), options, "written");
}

inline double diagonal(const Vertices& V) { return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm(); }

// Every slot moved by up to `fraction` of the diagonal, in a seeded random direction.
inline Vertices moved(const Vertices& V, double fraction) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  Vertices P = V;
  const double step = fraction * diagonal(V);
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    for (int k = 0; k < 3; ++k) P(i, k) += step * u(rng);
  return P;
}

/// A GLB as a .gltf whose buffer is the file `bin_name` beside it: (the JSON text, the buffer).
inline std::pair<std::string, std::string> split_glb(const std::string& glb, const std::string& bin_name) {
  std::uint32_t json_length, bin_length;
  std::memcpy(&json_length, glb.data() + 12, 4);
  std::memcpy(&bin_length, glb.data() + 20 + json_length, 4);
  nlohmann::json j = nlohmann::json::parse(glb.substr(20, json_length));
  j["buffers"][0]["uri"] = bin_name;
  return {j.dump(2), glb.substr(20 + json_length + 8, bin_length)};
}

}  // namespace meshmark::test
