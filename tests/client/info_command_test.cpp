// The `meshmark info` contract that scripts rely on: verdicts, exit status, JSON keys.

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/io/write_mesh.hpp"
#include "core/mesh/validate_mesh.hpp"

#include "tests/client/cli_runner.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

// `mesh`: a file of the real meshes, or "procedural/<shape>" (written here).
nlohmann::json info_json(const std::string& mesh, int& status) {
  const std::string path =
      test::is_procedural(mesh) ? test::procedural_file(mesh.substr(11)).string() : test::shared_mesh(mesh).string();
  const test::CliRun run = test::run_cli("info --json " + path);
  status = run.exit_status;
  return nlohmann::json::parse(run.out);
}

TEST(InfoCommand, ValidMeshesExitZeroWithAllKeys) {
  std::vector<std::string> names = {"procedural/creature", "procedural/creature_large"};
  if (test::shared_present()) names.insert(names.end(), {"bunny.obj", "mannequin.off", "spot.obj", "armadillo.obj"});
  for (const std::string& name : names) {
    int status;
    const nlohmann::json j = info_json(name, status);
    EXPECT_EQ(status, 0) << name;
    for (const char* key : {"vertices", "faces", "components", "boundary_edges", "boundary_loops", "nonmanifold_edges",
                            "nonmanifold_vertices", "genus", "orientation", "bbox_diagonal", "valid", "problems"})
      EXPECT_TRUE(j.contains(key)) << name << " lacks " << key;
    EXPECT_EQ(j["valid"], true) << name;
    EXPECT_EQ(j["genus"], 0) << name;
    EXPECT_EQ(j["orientation"], "outward") << name;
  }
}

TEST(InfoCommand, MeshesTheSphereCannotTakeNameTheirBasisAndWhy) {
  int status;
  nlohmann::json torus = info_json("procedural/torus", status);
  EXPECT_EQ(status, 0);
  EXPECT_EQ(torus["genus"], 1);
  EXPECT_EQ(torus["closed_genus_zero"], false);
  EXPECT_EQ(torus["basis"], "bumps");
  EXPECT_NE(torus["basis_reason"].get<std::string>().find("genus 1"), std::string::npos);
  EXPECT_NE(torus["sphere_problems"][0].get<std::string>().find("genus 1"), std::string::npos);

  nlohmann::json holes = info_json("procedural/creature_holes", status);
  EXPECT_EQ(status, 0);
  EXPECT_EQ(holes["boundary_loops"], 3);
  EXPECT_EQ(holes["basis"], "sphere-filled");

  nlohmann::json pinched = info_json("procedural/pinched", status);
  EXPECT_EQ(status, 0);
  EXPECT_TRUE(pinched["genus"].is_null());
  EXPECT_EQ(pinched["nonmanifold_vertices"], 1);
  EXPECT_EQ(pinched["basis"], "bumps");
  const int pinch = validate_mesh(test::procedural_mesh("pinched")).nonmanifold_vertex_examples.at(0);
  EXPECT_NE(pinched["sphere_problems"][0].get<std::string>().find("vertex " + std::to_string(pinch)),
            std::string::npos);

  const test::CliRun text = test::run_cli("info " + test::procedural_file("torus", "off").string());
  EXPECT_NE(text.out.find("watermark basis       bumps: "), std::string::npos) << text.out;
}

TEST(InfoCommand, AMeshTooSmallToCarryAPayloadExitsOneWithTheReason) {
  const auto path = std::filesystem::temp_directory_path() / ("meshmark-info-" + std::to_string(::getpid()) + ".obj");
  write_mesh(path, test::cube());
  const test::CliRun run = test::run_cli("info --json " + path.string());
  std::filesystem::remove(path);
  EXPECT_EQ(run.exit_status, 1);
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["basis"], "none");
  EXPECT_NE(j["problems"][0].get<std::string>().find("at least 100"), std::string::npos);
}

TEST(InfoCommand, UnreadableFileExitsTwoWithAMessage) {
  const test::CliRun run = test::run_cli("info /nonexistent/model.obj", true);
  EXPECT_EQ(run.exit_status, 2);
  EXPECT_NE(run.out.find("cannot open"), std::string::npos);
}

TEST(SphereCommand, ReportsABijectiveMapAsJson) {
  const test::CliRun run = test::run_cli("sphere --json " + test::procedural_file("creature").string());
  ASSERT_EQ(run.exit_status, 0);
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["flipped_faces"], 0);
  EXPECT_NEAR(j["degree"].get<double>(), 1.0, 1e-9);
  for (const char* key : {"method", "progressive", "seconds", "area_distortion"}) EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["method"], "progressive");
}

TEST(SphereCommand, RefusesAGenusOneMesh) {
  const test::CliRun run = test::run_cli("sphere " + test::procedural_file("torus", "off").string(), true);
  EXPECT_EQ(run.exit_status, 1);
  EXPECT_NE(run.out.find("genus 1"), std::string::npos);
}

}  // namespace
}  // namespace meshmark
