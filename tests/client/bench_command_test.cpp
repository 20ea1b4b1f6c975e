// `meshmark bench`: every stage is measured, with time and memory, and the totals add up.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/evaluation/benchmark.hpp"
#include "tests/client/cli_runner.hpp"
#include "tests/test_data.hpp"

namespace meshmark::test {
namespace {

TEST(BenchCommand, MeasuresEveryStageWithTimeAndPeakMemory) {
  const CliRun run = run_cli("bench --json --runs 1 --subdivide 0 --meshes " + procedural_file("creature").string());
  ASSERT_EQ(run.exit_status, 0) << run.out;
  const auto report = nlohmann::json::parse(run.out);
  ASSERT_EQ(report.at("meshes").size(), 1u);
  const auto& mesh = report["meshes"][0];
  EXPECT_EQ(mesh.value("vertices", 0), procedural_mesh("creature").V.rows());
  std::map<std::string, double> seconds;
  for (const auto& stage : mesh.at("stages")) {
    seconds[stage.at("stage")] = stage.at("median_seconds");
    EXPECT_GT(stage.value("peak_mib", 0.0), 1.0) << stage.dump();
  }
  for (const auto& [stage, what] : benchmark_stages()) {  // every stage of the sphere's path
    if (stage != "bumps") {
      EXPECT_TRUE(seconds.count(stage)) << stage;
    }
  }
  EXPECT_FALSE(seconds.count("bumps"));
  double cold_stages = 0;
  for (const char* s : {"load", "validate", "parameterize", "grid_and_sampling", "embed.plan", "embed.synthesis",
                        "embed.apply", "write"})
    cold_stages += seconds[s];
  EXPECT_GE(seconds["total.cold_embed"], cold_stages);
  EXPECT_LT(seconds["total.cold_embed"], cold_stages * 1.5 + 0.05);
  EXPECT_GE(seconds["total.detect"],
            seconds["detect.align"] + seconds["detect.read"] + seconds["detect.estimate"] + seconds["detect.decode"]);
  std::map<std::string, double> floor_ratio;  // one run: the stage ÷ that run's load + write
  for (const auto& stage : mesh.at("stages")) floor_ratio[stage.at("stage")] = stage.at("floor_ratio");
  EXPECT_NEAR(floor_ratio["load"] + floor_ratio["write"], 1.0, 1e-9);
  EXPECT_NEAR(floor_ratio["total.cold_embed"] * (seconds["load"] + seconds["write"]), seconds["total.cold_embed"],
              1e-6 * seconds["total.cold_embed"]);
}

TEST(BenchCommand, WholeProcessesSideBySideWithAnotherCommand) {
  const CliRun run = run_cli("bench --json --runs 1 --subdivide 0 --meshes " + procedural_file("creature").string() +
                             " --versus 'cold embed=cp {mesh} {out}'");
  ASSERT_EQ(run.exit_status, 0) << run.out;
  const auto report = nlohmann::json::parse(run.out);
  ASSERT_EQ(report.at("meshes").size(), 1u);
  std::map<std::string, nlohmann::json> rows;
  for (const auto& row : report["meshes"][0].at("commands")) rows[row.at("command")] = row;
  for (const char* ours : {"cold embed", "warm embed", "detect --record", "detect --original"}) {
    ASSERT_TRUE(rows.count(ours)) << ours;
    EXPECT_GT(rows[ours].value("peak_mib", 0.0), 1.0) << ours;
    EXPECT_GT(rows[ours].value("floor_ratio", 0.0), 0.0) << ours;
  }
  EXPECT_DOUBLE_EQ(rows.at(report.at("floor")).value("floor_ratio", 0.0), 1.0);
  const auto& theirs = rows.at("cold embed (theirs)");
  EXPECT_NEAR(theirs.value("ours_over_theirs", 0.0),
              rows["cold embed"].value("median_seconds", 0.0) / theirs.value("median_seconds", 1.0), 1e-9);
  EXPECT_GT(theirs.value("ours_over_theirs", 0.0), 1.0);  // a copy is cheaper than an embed
  EXPECT_FALSE(rows["warm embed"].contains("ours_over_theirs"));
}

TEST(BenchCommand, AVersusWithoutANameIsRefused) {
  const CliRun run = run_cli("bench --versus 'cp {mesh} {out}'", true);
  EXPECT_NE(run.exit_status, 0);
  EXPECT_NE(run.out.find("NAME=COMMAND"), std::string::npos) << run.out;
}

TEST(BenchCommand, AMeshOnBumpsIsMeasuredWithItsOwnStages) {
  const CliRun run =
      run_cli("bench --json --runs 1 --subdivide 0 --meshes " + procedural_file("torus", "off").string());
  ASSERT_EQ(run.exit_status, 0) << run.out;
  const auto report = nlohmann::json::parse(run.out);
  std::map<std::string, double> seconds;
  for (const auto& stage : report["meshes"][0].at("stages")) seconds[stage.at("stage")] = stage.at("median_seconds");
  EXPECT_TRUE(seconds.count("bumps"));
  EXPECT_FALSE(seconds.count("parameterize"));
  EXPECT_TRUE(seconds.count("total.detect"));
}

TEST(GrowthExponent, RecoversThePowerOfAPowerLaw) {
  EXPECT_NEAR(growth_exponent({1e3, 1e4, 1e5}, {2.0, 2.0 * std::pow(10.0, 1.5), 2.0 * 1000.0}), 1.5, 1e-12);
  EXPECT_NEAR(growth_exponent({35e3, 43e3, 557e3}, {1, 1, 1}), 0.0, 1e-12);
}

}  // namespace
}  // namespace meshmark::test
