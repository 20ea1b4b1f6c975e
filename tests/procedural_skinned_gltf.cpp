// A skinned, morphing, animated glTF binary made here (see procedural_assets.hpp).

#include <algorithm>
#include <cstring>

#include <nlohmann/json.hpp>

#include "tests/procedural_assets.hpp"
#include "tests/procedural_meshes.hpp"

namespace meshmark::test {
namespace {

using nlohmann::json;

// The binary buffer, one view per appended block (each 4-byte aligned).
struct BufferBuilder {
  std::string bytes;
  json views = json::array();

  template <typename T>
  std::size_t add(const std::vector<T>& values) {
    views.push_back({{"buffer", 0}, {"byteOffset", bytes.size()}, {"byteLength", values.size() * sizeof(T)}});
    bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
    bytes.resize((bytes.size() + 3) / 4 * 4, '\0');
    return views.size() - 1;
  }
};

json accessor(std::size_t view, int component_type, std::size_t count, const char* type) {
  return {{"bufferView", view}, {"componentType", component_type}, {"count", count}, {"type", type}};
}

json bounds_of(const std::vector<float>& values, int width, const char* which) {
  json out = json::array();
  for (int k = 0; k < width; ++k) {
    float bound = values[static_cast<std::size_t>(k)];
    for (std::size_t i = static_cast<std::size_t>(k); i < values.size(); i += static_cast<std::size_t>(width))
      bound = std::strcmp(which, "min") == 0 ? std::min(bound, values[i]) : std::max(bound, values[i]);
    out.push_back(bound);
  }
  return out;
}

json with_bounds(json a, const std::vector<float>& values, int width) {
  a["min"] = bounds_of(values, width, "min");
  a["max"] = bounds_of(values, width, "max");
  return a;
}

// The creature, each vertex bound to joint 0 or 1 by its height, a morph target that pushes it
// outward, and an animation that turns joint 1 a quarter about z.
}  // namespace

std::string skinned_glb() {
  const Mesh& mesh = procedural_mesh("creature");
  const auto n = static_cast<std::size_t>(mesh.V.rows());
  std::vector<float> positions, deltas, weights;
  std::vector<std::uint8_t> joints;
  for (std::size_t v = 0; v < n; ++v) {
    for (int k = 0; k < 3; ++k) {
      positions.push_back(static_cast<float>(mesh.V(static_cast<Eigen::Index>(v), k)));
      deltas.push_back(0.05f * positions.back());
    }
    const float upper = std::clamp(0.5f + positions[3 * v + 1], 0.0f, 1.0f);
    joints.insert(joints.end(), {0, 1, 0, 0});
    weights.insert(weights.end(), {1 - upper, upper, 0, 0});
  }
  std::vector<std::uint32_t> indices;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) indices.push_back(static_cast<std::uint32_t>(mesh.F(f, k)));
  const std::vector<float> inverse_binds = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0,    0, 1,
                                            1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -0.5, 0, 1};
  const std::vector<float> times = {0, 1}, turns = {0, 0, 0, 1, 0, 0, 0.70710677f, 0.70710677f};

  BufferBuilder b;
  json accessors = json::array();
  accessors.push_back(with_bounds(accessor(b.add(positions), 5126, n, "VEC3"), positions, 3));
  accessors.push_back(accessor(b.add(joints), 5121, n, "VEC4"));
  accessors.push_back(accessor(b.add(weights), 5126, n, "VEC4"));
  accessors.push_back(with_bounds(accessor(b.add(deltas), 5126, n, "VEC3"), deltas, 3));
  accessors.push_back(accessor(b.add(indices), 5125, indices.size(), "SCALAR"));
  accessors.push_back(accessor(b.add(inverse_binds), 5126, 2, "MAT4"));
  accessors.push_back(with_bounds(accessor(b.add(times), 5126, 2, "SCALAR"), times, 1));
  accessors.push_back(accessor(b.add(turns), 5126, 2, "VEC4"));
  json primitive = {{"attributes", {{"POSITION", 0}, {"JOINTS_0", 1}, {"WEIGHTS_0", 2}}}, {"indices", 4}};
  primitive["targets"] = json::array({{{"POSITION", 3}}});
  json j = {{"asset", {{"version", "2.0"}}}, {"scene", 0}, {"accessors", accessors}, {"bufferViews", b.views}};
  j["buffers"] = json::array({{{"byteLength", b.bytes.size()}}});
  j["scenes"] = json::array({{{"nodes", json::array({0, 1})}}});
  j["nodes"] = json::array(
      {{{"mesh", 0}, {"skin", 0}}, {{"children", json::array({2})}}, {{"translation", json::array({0, 0.5, 0})}}});
  j["meshes"] = json::array({{{"primitives", json::array({primitive})}, {"weights", json::array({0.5})}}});
  j["skins"] = json::array({{{"joints", json::array({1, 2})}, {"inverseBindMatrices", 5}}});
  j["animations"] =
      json::array({{{"samplers", json::array({{{"input", 6}, {"output", 7}}})},
                    {"channels", json::array({{{"sampler", 0}, {"target", {{"node", 2}, {"path", "rotation"}}}}})}}});
  std::string text = j.dump();
  text.resize((text.size() + 3) / 4 * 4, ' ');
  const auto u32 = [](std::size_t x) {
    const auto v = static_cast<std::uint32_t>(x);
    return std::string(reinterpret_cast<const char*>(&v), 4);
  };
  return "glTF" + u32(2) + u32(12 + 8 + text.size() + 8 + b.bytes.size()) + u32(text.size()) + "JSON" + text +
         u32(b.bytes.size()) + std::string("BIN\0", 4) + b.bytes;
}

}  // namespace meshmark::test
