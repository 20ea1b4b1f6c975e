#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <set>

#include "core/io/base64.hpp"
#include "core/io/document_surface.hpp"
#include "core/io/mesh_document.hpp"
#include "core/io/mesh_io_error.hpp"
#include "tests/io/document_helpers.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

using test::moved;
using test::read_written;

// The JSON part of a .gltf or .glb.
nlohmann::json gltf_json(const std::string& bytes) {
  if (bytes.rfind("glTF", 0) != 0) return nlohmann::json::parse(bytes);
  std::uint32_t length;
  std::memcpy(&length, bytes.data() + 12, 4);
  return nlohmann::json::parse(bytes.substr(20, length));
}

// The JSON with what moving positions may change taken out: accessor bounds, and the lengths and
// offsets of buffers and views (a Draco stream encoded again has another length).
nlohmann::json without_bounds(nlohmann::json j) {
  for (auto& a : j["accessors"]) {
    a.erase("min");
    a.erase("max");
  }
  for (auto& v : j["bufferViews"]) {
    v.erase("byteLength");
    v.erase("byteOffset");
  }
  for (auto& b : j["buffers"]) b.erase("byteLength");
  return j;
}

TEST(GltfDocument, MovingPositionsChangesOnlyBoundsInTheJson) {
  MESHMARK_NEEDS_SHARED();
  for (const char* name :
       {"Duck/glTF-Binary/Duck.glb", "Avocado-Quantized/glTF-Quantized/Avocado.gltf",
        "WaterBottle-Draco/glTF-Draco/WaterBottle.gltf", "CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb"}) {
    const auto path = test::shared_asset(name);
    const auto doc = read_document_file(path);
    const DocumentFiles files = doc->write(moved(doc->slot_positions(), 2e-3), {});
    const std::string original = read_file_bytes(path, 1u << 30);
    EXPECT_NE(files.at(""), original) << name;
    nlohmann::json before = without_bounds(gltf_json(original)), after = without_bounds(gltf_json(files.at("")));
    if (std::string(name).find("Quantized") != std::string::npos) {
      // Its u16 positions start at 0: moved below, the mesh shifts and its node takes it back.
      EXPECT_NE(after["nodes"][0]["translation"], before["nodes"][0]["translation"]);
      after["nodes"][0].erase("translation");
      before["nodes"][0].erase("translation");
    }
    EXPECT_EQ(after, before) << name;
  }
}

// Byte ranges of the buffer views no POSITION, NORMAL or TANGENT accessor reads (indices, texture
// coordinates, images, morph targets) are the same after positions move.
TEST(GltfDocument, ViewsWithoutPositionsOrNormalsKeepTheirBytes) {
  MESHMARK_NEEDS_SHARED();
  const auto path = test::shared_asset("Duck/glTF-Binary/Duck.glb");
  const auto doc = read_document_file(path);
  const std::string original = read_file_bytes(path, 1u << 30);
  const std::string written = doc->write(moved(doc->slot_positions(), 2e-3), {}).at("");
  const nlohmann::json j = gltf_json(original);
  std::set<std::size_t> moving_views;
  for (const auto& mesh : j["meshes"])
    for (const auto& p : mesh["primitives"])
      for (const char* a : {"POSITION", "NORMAL", "TANGENT"})
        if (p["attributes"].contains(a))
          moving_views.insert(j["accessors"][p["attributes"][a].get<std::size_t>()]["bufferView"].get<std::size_t>());
  const auto bin_chunk = [](const std::string& glb) {  // the JSON chunk's length moves it
    std::uint32_t json_length;
    std::memcpy(&json_length, glb.data() + 12, 4);
    return glb.substr(20 + json_length + 8);
  };
  const std::string before = bin_chunk(original), after = bin_chunk(written);
  ASSERT_EQ(before.size(), after.size());
  std::size_t checked = 0;
  for (std::size_t v = 0; v < j["bufferViews"].size(); ++v) {
    if (moving_views.count(v)) continue;
    const std::size_t offset = j["bufferViews"][v].value("byteOffset", std::size_t{0});
    const std::size_t length = j["bufferViews"][v]["byteLength"];
    EXPECT_EQ(after.substr(offset, length), before.substr(offset, length)) << "view " << v;
    checked += length;
  }
  EXPECT_GT(checked, 60'000u);  // the embedded texture is among them
}

TEST(GltfDocument, ChangedExternalBufferTakesTheGivenName) {
  MESHMARK_NEEDS_SHARED();
  const auto path = test::shared_asset("Avocado/glTF/Avocado.gltf");
  const auto doc = read_document_file(path);
  const DocumentFiles files =
      doc->write(moved(doc->slot_positions(), 2e-3), {}, [](const std::string& uri) { return "marked-" + uri; });
  ASSERT_EQ(files.count("marked-Avocado.bin"), 1u);
  EXPECT_EQ(files.count("Avocado.bin"), 0u);
  EXPECT_EQ(gltf_json(files.at(""))["buffers"][0]["uri"], "marked-Avocado.bin");
  EXPECT_EQ(read_written(files, path)->slot_positions().rows(), doc->slot_positions().rows());
}

TEST(GltfDocument, InstancedMeshHasItsSlotsOnceAndEveryInstanceInTheScene) {
  MESHMARK_NEEDS_SHARED();
  const auto doc = read_document_file(test::shared_asset("CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb"));
  std::size_t stored = 0, instanced = 0;
  for (const DocumentPart& p : doc->parts()) {
    stored += p.stored_vertices;
    instanced += p.stored_vertices * p.instances;
  }
  EXPECT_EQ(static_cast<std::size_t>(doc->slot_positions().rows()), stored);
  EXPECT_GT(instanced, stored);
  EXPECT_EQ(static_cast<std::size_t>(doc->scene().V.rows()), instanced);
}

// A tetrahedron drawn by two nodes: as it is, and turned a quarter about z, doubled, moved along x.
std::string instanced_tetrahedron_json() {
  std::string bin;
  const float corners[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const auto& c : corners) bin.append(reinterpret_cast<const char*>(c), sizeof c);
  const std::uint16_t triangles[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  bin.append(reinterpret_cast<const char*>(triangles), sizeof triangles);
  const double half = std::sqrt(0.5);
  const nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"buffers",
       {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64_encode(bin)}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteLength", 48}}, {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 24}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", 1}, {"componentType", 5123}, {"count", 12}, {"type", "SCALAR"}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
      {"nodes",
       {{{"mesh", 0}},
        {{"mesh", 0}, {"translation", {5, 0, 0}}, {"rotation", {0, 0, half, half}}, {"scale", {2, 2, 2}}}}}};
  return j.dump();
}

std::unique_ptr<MeshDocument> instanced_tetrahedron() {
  return read_document(instanced_tetrahedron_json(), MeshFormat::gltf, {}, "instanced.gltf");
}

// The surface holds every instance; a slot takes the mean of its instances' moves in its own frame,
// so that a move every instance makes alike is written exactly.
TEST(GltfDocument, AnInstancedMeshIsPartOfTheSurfaceOncePerInstanceAndItsSlotsTakeTheirMeanMove) {
  const auto doc = instanced_tetrahedron();
  ASSERT_EQ(doc->slot_positions().rows(), 4);
  ASSERT_EQ(doc->further_instances().size(), 1u);
  const WeldedSurface surface = document_surface(*doc);
  ASSERT_EQ(surface.mesh.V.rows(), 8);
  ASSERT_EQ(surface.mesh.F.rows(), 8);
  Eigen::Matrix3d turn_and_double;
  turn_and_double << 0, -2, 0, 2, 0, 0, 0, 0, 2;
  const std::vector<int>& repeats = doc->further_instances()[0].slots;
  const auto second = [&](int slot) {  // the second instance's surface vertex of a slot
    const auto k = std::find(repeats.begin(), repeats.end(), slot) - repeats.begin();
    return surface.vertex_of[4 + static_cast<std::size_t>(k)];
  };
  for (int slot = 0; slot < 4; ++slot) {
    const Eigen::Vector3d expected =
        turn_and_double * doc->slot_positions().row(slot).transpose() + Eigen::Vector3d(5, 0, 0);
    EXPECT_LT((surface.mesh.V.row(second(slot)).transpose() - expected).norm(), 1e-6) << slot;
  }
  // Slot 0 moved by (1, 0, 0) in the first instance and by (0, 0, 3) in its own frame in the
  // second: it takes the mean. Slot 1 moves alike in both: exactly that move.
  Vertices V = surface.mesh.V;
  V.row(surface.vertex_of[0]) += Eigen::RowVector3d(0.01, 0, 0);
  V.row(second(0)) += (turn_and_double * Eigen::Vector3d(0, 0, 0.03)).transpose();
  V.row(surface.vertex_of[1]) += Eigen::RowVector3d(0, 0.02, 0);
  V.row(second(1)) += (turn_and_double * Eigen::Vector3d(0, 0.02, 0)).transpose();
  const MovedSlots moved_slots = move_slots(*doc, surface, V);
  EXPECT_LT((moved_slots.positions.row(0) - Eigen::RowVector3d(0.005, 0, 0.015)).norm(), 1e-12);
  EXPECT_LT((moved_slots.positions.row(1) - Eigen::RowVector3d(1, 0.02, 0)).norm(), 1e-12);
  EXPECT_EQ(moved_slots.positions.row(2), doc->slot_positions().row(2));
  // Written and read again, the second instance shows slot 1's move, turned and doubled.
  const auto written = read_document(doc->write(moved_slots.positions, moved_slots.rotations).at(""), MeshFormat::gltf,
                                     {}, "written.gltf");
  const WeldedSurface again = document_surface(*written);
  const auto k = std::find(repeats.begin(), repeats.end(), 1) - repeats.begin();
  EXPECT_LT((again.mesh.V.row(again.vertex_of[4 + static_cast<std::size_t>(k)]) - V.row(second(1))).norm(), 1e-6);
}

// Nodes that each list the next one twice: 2^40 placements of the tetrahedron in a kilobyte, and
// 2^40 visits of nodes without a mesh. Both refused once they pass the scene's budget.
TEST(GltfDocument, ANodeHierarchyThatRepeatsItselfIsRefusedWithinTheSceneBudget) {
  for (const bool with_mesh : {true, false}) {
    nlohmann::json j = nlohmann::json::parse(instanced_tetrahedron_json());
    nlohmann::json nodes = nlohmann::json::array();
    for (int level = 0; level < 40; ++level) nodes.push_back({{"children", {level + 1, level + 1}}});
    nodes.push_back(with_mesh ? nlohmann::json{{"mesh", 0}} : nlohmann::json::object());
    nodes.push_back({{"mesh", 0}});  // so that a mesh is drawn either way
    j["nodes"] = nodes;
    j["scenes"] = {{{"nodes", {0, 41}}}};
    j["scene"] = 0;
    try {
      read_document(j.dump(), MeshFormat::gltf, {}, "dag.gltf");
      FAIL() << "read";
    } catch (const MeshLimitError& e) {
      EXPECT_NE(std::string(e.what()).find("repeats itself"), std::string::npos) << e.what();
    }
  }
}

// JSON whose parsed tree would cost ~80 times its text is refused before it is parsed.
TEST(GltfDocument, JsonWithMoreValuesThanTheBudgetIsRefusedUnparsed) {
  std::string text = instanced_tetrahedron_json();
  std::string extras = "\"extras\":[0";
  for (std::size_t k = 0; k < kMaxGltfJsonValues; ++k) extras += ",0";
  text.insert(1, extras + "],");
  try {
    read_document(text, MeshFormat::gltf, {}, "values.gltf");
    FAIL() << "read";
  } catch (const MeshLimitError& e) {
    EXPECT_NE(std::string(e.what()).find("more than " + std::to_string(kMaxGltfJsonValues) + " values"),
              std::string::npos)
        << e.what();
  }
}

// Six buffers naming one file: refused after reading it once (each buffer is written back as a
// file of its own, so a file named twice would be held twice and keep only one buffer's changes).
TEST(GltfDocument, BuffersNamingOneFileAreRefusedAfterOneRead) {
  nlohmann::json j = nlohmann::json::parse(instanced_tetrahedron_json());
  const std::size_t length = j["buffers"][0]["byteLength"];
  j["buffers"] = nlohmann::json::array();
  for (int k = 0; k < 6; ++k) j["buffers"].push_back({{"uri", "a.bin"}, {"byteLength", length}});
  int reads = 0;
  DocumentReadOptions options;
  options.companion = [&](const std::string&) {
    ++reads;
    return std::string(length, '\0');
  };
  try {
    read_document(j.dump(), MeshFormat::gltf, options, "shared.gltf");
    FAIL() << "read";
  } catch (const MeshIoError& e) {
    EXPECT_NE(std::string(e.what()).find("buffers 0 and 1 both name the file 'a.bin'"), std::string::npos) << e.what();
  }
  EXPECT_EQ(reads, 1);
}

// A texture-coordinate accessor reading the bytes of the positions: moving them would change it.
TEST(GltfDocument, PositionsSharingBytesWithOtherDataAreNotWritten) {
  std::string bin;
  const float corners[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const auto& c : corners) bin.append(reinterpret_cast<const char*>(c), sizeof c);
  const std::uint16_t triangles[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  bin.append(reinterpret_cast<const char*>(triangles), sizeof triangles);
  const nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"buffers",
       {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64_encode(bin)}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 24}},
        {{"buffer", 0}, {"byteLength", 32}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", 1}, {"componentType", 5123}, {"count", 12}, {"type", "SCALAR"}},
        {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 2}}}, {"indices", 1}}}}}}},
      {"nodes", {{{"mesh", 0}}}}};
  const auto doc = read_document(j.dump(), MeshFormat::gltf, {}, "aliased.gltf");
  ASSERT_EQ(doc->slot_positions().rows(), 4);
  Vertices P = doc->slot_positions();
  P(0, 0) += 0.1;
  try {
    doc->write(P, {});
    FAIL() << "written";
  } catch (const MeshIoError& e) {
    EXPECT_NE(std::string(e.what()).find("share bytes with other data"), std::string::npos) << e.what();
  }
}

TEST(GltfDocument, RefusesWhatIsNotGltf2) {
  const auto error = [](const std::string& bytes, MeshFormat format) {
    try {
      read_document(bytes, format, {}, "input");
    } catch (const MeshIoError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error(R"({"asset":{"version":"1.0"}})", MeshFormat::gltf).find("only glTF 2.0"), std::string::npos);
  EXPECT_NE(error("not json", MeshFormat::gltf).find("not a JSON object"), std::string::npos);
  EXPECT_NE(error(std::string(40, 'x'), MeshFormat::glb).find("no 'glTF' magic"), std::string::npos);
  EXPECT_NE(error(R"({"asset":{"version":"2.0"},"buffers":[{"uri":"a.bin","byteLength":4}]})", MeshFormat::gltf)
                .find("cannot be read here"),
            std::string::npos);
  EXPECT_NE(error(R"({"asset":{"version":"2.0"}})", MeshFormat::gltf).find("no triangle primitive"), std::string::npos);
}

}  // namespace
}  // namespace meshmark
