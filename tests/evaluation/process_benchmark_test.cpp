// Whole processes timed side by side: what a command costs, as a multiple of the floor timed in
// the same round, and what it printed when it failed.

#include "core/evaluation/process_benchmark.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/evaluation/host_load.hpp"

namespace meshmark::test {
namespace {

TEST(SubstitutePaths, QuotesEveryPlaceholderForTheShell) {
  EXPECT_EQ(substitute_paths("cp {mesh} {out} && cat {mesh}", {{"mesh", "/a b/it's.obj"}, {"out", "/o.obj"}}),
            "cp '/a b/it'\\''s.obj' '/o.obj' && cat '/a b/it'\\''s.obj'");
  EXPECT_EQ(substitute_paths("{work}/copy{ext}", {{"work", "/w"}, {"ext", ".ply"}}), "'/w'/copy'.ply'");
  EXPECT_EQ(substitute_paths("echo {unknown}", {{"mesh", "/m"}}), "echo {unknown}");
  // A path that holds a placeholder's text stays that path, quoted once.
  EXPECT_EQ(substitute_paths("cp {mesh} {out}", {{"mesh", "/d/{out}.obj"}, {"out", "/o b"}}),
            "cp '/d/{out}.obj' '/o b'");
  EXPECT_EQ(substitute_paths("{mesh", {{"mesh", "/m"}}), "{mesh");
}

TEST(RunTimedProcess, MeasuresTheWallTimeAndThePeakOfWhatTheShellRan) {
  const ProcessRun idle = run_timed_process("sleep 0.2");
  EXPECT_GE(idle.seconds, 0.2);
  EXPECT_GT(idle.peak_mib, 0.0);
  // dd reads into a 200 MB buffer: the peak is the shell's child's, not the shell's.
  const ProcessRun big = run_timed_process("dd if=/dev/zero of=/dev/null bs=200M count=1 status=none && true");
  EXPECT_GT(big.peak_mib, 150.0);
  EXPECT_LT(idle.peak_mib, 50.0);
}

TEST(RunTimedProcess, AFailureSaysWhatTheCommandPrinted) {
  try {
    run_timed_process("echo the mesh is empty >&2; exit 3");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("exit status 3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("the mesh is empty"), std::string::npos) << e.what();
  }
}

TEST(ProcessBenchmark, EachCommandIsAMultipleOfTheFloorOfItsRound) {
  const auto mesh = std::filesystem::temp_directory_path() / "process-benchmark-test.obj";
  std::ofstream(mesh) << "v 0 0 0\n";
  ProcessBenchmarkOptions options;
  options.meshes = {mesh};
  options.floor = {"floor", "sleep 0.1; cp {mesh} {out}"};
  options.setup = {"cp {mesh} {work}/copy{ext}"};
  options.commands = {{"three floors", "sleep 0.3; test -f {work}/copy{ext} && test ! -e {out}"},
                      {"writes", "cp {mesh} {out} && test -f {out}"}};
  options.runs = 3;
  const auto figures = run_process_benchmark(options);
  ASSERT_EQ(figures.size(), 1u);
  const MeshProcessFigures& m = figures[0];
  ASSERT_EQ(m.commands.size(), 3u);
  EXPECT_EQ(m.commands[0].name, "floor");
  EXPECT_DOUBLE_EQ(m.commands[0].median_floor_ratio, 1.0);
  const CommandFigures* slow = m.find("three floors");
  ASSERT_NE(slow, nullptr);
  EXPECT_EQ(slow->seconds.size(), 3u);
  EXPECT_GE(slow->median_seconds, 0.3);
  EXPECT_GT(slow->median_floor_ratio, 2.0);  // 3 on an idle machine; fork and exec add to both
  EXPECT_LT(slow->median_floor_ratio, 3.5);
  EXPECT_LT(m.find("writes")->median_floor_ratio, 1.0);
  EXPECT_GE(m.steal_fraction, 0.0);
  std::filesystem::remove(mesh);
}

TEST(HostLoad, TheMedianOfEvenAndOddCounts) {
  EXPECT_DOUBLE_EQ(median({3, 1, 2}), 2.0);
  EXPECT_DOUBLE_EQ(median({4, 1, 3, 2}), 2.5);
  EXPECT_DOUBLE_EQ(median({}), 0.0);
  const CpuJiffies now = cpu_jiffies();
  EXPECT_GT(now.total, 0.0);
  EXPECT_DOUBLE_EQ(steal_fraction(now, now), 0.0);
}

}  // namespace
}  // namespace meshmark::test
