// The `embed` and `detect` command-line contract: names, JSON keys, exit statuses.

#include <gtest/gtest.h>

#include <set>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/attacks/reorder.hpp"
#include "core/attacks/similarity_transform.hpp"
#include "core/io/mesh_document.hpp"
#include "core/io/read_mesh.hpp"
#include "core/io/write_mesh.hpp"
#include "proto/copy_record.hpp"
#include "tests/build_paths.hpp"
#include "tests/client/cli_runner.hpp"
#include "tests/server/api_client.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

// In a folder of this process's own, removed at exit: a folder named by the process id outlived
// it, and a later process given the same id found an old copy where a refused embed wrote none.
std::filesystem::path temp_file(const std::string& name) { return test::process_temp_folder("meshmark-cli") / name; }

TEST(EmbedAndDetectCommands, RoundTripWithTheDocumentedJson) {
  const std::string original = test::procedural_file("creature").string();
  const std::string marked = temp_file("creature_marked.ply").string();
  const test::CliRun embed =
      test::run_cli("embed " + original + " " + marked + " --key k1 --payload 0123456789abcdef --json");
  ASSERT_EQ(embed.exit_status, 0) << embed.out;
  const nlohmann::json e = nlohmann::json::parse(embed.out);
  for (const char* key : {"parameters", "grid", "seconds", "distortion"}) EXPECT_TRUE(e.contains(key)) << key;
  EXPECT_TRUE(e["grid"].contains("level"));
  EXPECT_TRUE(e["grid"].contains("samples"));
  EXPECT_LE(e["distortion"]["mrms"].get<double>(), 0.0005);
  EXPECT_TRUE(e["distortion"].contains("hausdorff"));
  EXPECT_EQ(e["parameters"]["scheme"], "spread");
  // Every second of the process is in a stage: the stages (parameterization is part of prepare)
  // add up to the total but for what runs before and after them (parsing the command line).
  const auto stages_and_total = [](const nlohmann::json& seconds) {
    double stages = 0;
    for (const auto& [stage, s] : seconds.items())
      if (stage != "total" && stage != "parameterization") stages += s.get<double>();
    return std::pair{stages, seconds.at("total").get<double>()};
  };
  for (const char* stage : {"load", "prepare", "encode", "verify", "write", "distortion", "record"})
    EXPECT_TRUE(e["seconds"].contains(stage)) << stage;
  const auto [embed_stages, embed_total] = stages_and_total(e["seconds"]);
  EXPECT_LE(embed_stages, embed_total);
  EXPECT_GE(embed_stages, 0.9 * embed_total - 0.05) << e["seconds"].dump();

  const test::CliRun detect =
      test::run_cli("detect " + marked + " --original " + original + " --key k1 --expect 0123456789abcdef --json");
  ASSERT_EQ(detect.exit_status, 0) << detect.out;
  const nlohmann::json d = nlohmann::json::parse(detect.out);
  for (const char* key : {"detected", "payload", "bits", "ber", "p_value", "correlation", "alignment"})
    EXPECT_TRUE(d.contains(key)) << key;
  for (const char* key : {"rms", "scale", "iterations"}) EXPECT_TRUE(d["alignment"].contains(key)) << key;
  EXPECT_EQ(d["detected"], true);
  EXPECT_EQ(d["payload"], "0123456789abcdef");
  EXPECT_EQ(d["bits"], 64);
  EXPECT_EQ(d["ber"], 0.0);
  EXPECT_LT(d["p_value"].get<double>(), 1e-9);
  for (const char* stage : {"original", "suspect"}) EXPECT_TRUE(d["seconds"].contains(stage)) << stage;
  const auto [detect_stages, detect_total] = stages_and_total(d["seconds"]);
  EXPECT_LE(detect_stages, detect_total);
}

// A regular icosphere fits as well turned sixty ways, by its shape and by its vertices alike: a
// turned copy of it cannot be registered, so the self-check refuses the copy before anything is
// written, saying why. (Heavy: a ball's registration is slow under the sanitizers.)
TEST(SelfCheckCommands, ACopyThatDoesNotReadBackIsRefusedAndNeitherItNorARecordIsWritten) {
  const std::string original = temp_file("ball.obj").string();
  write_mesh(original, test::icosphere(4));
  const std::string marked = temp_file("ball_marked.ply").string();
  const test::CliRun embed =
      test::run_cli("embed " + original + " " + marked + " --key k1 --payload 0123456789abcdef", true);
  EXPECT_EQ(embed.exit_status, 2) << embed.out;
  EXPECT_NE(embed.out.find("does not read back"), std::string::npos) << embed.out;
  EXPECT_NE(embed.out.find("was not handed out"), std::string::npos) << embed.out;
  EXPECT_NE(embed.out.find("nearly symmetric"), std::string::npos) << embed.out;
  EXPECT_FALSE(std::filesystem::exists(marked));
  EXPECT_FALSE(std::filesystem::exists(test::record_of(marked, "0123456789abcdef")));
  // --no-verify hands it out all the same, and says so in the output and the record.
  const test::CliRun unchecked =
      test::run_cli("embed " + original + " " + marked + " --key k1 --payload 0123456789abcdef --no-verify");
  ASSERT_EQ(unchecked.exit_status, 0) << unchecked.out;
  EXPECT_NE(unchecked.out.find("not verified"), std::string::npos) << unchecked.out;
  EXPECT_EQ(nlohmann::json::parse(read_file_bytes(test::record_of(marked, "0123456789abcdef"), 1 << 20))["verified"],
            false);
}

// A ball tessellated unevenly, as exporters leave one: its shape fits every turn, and the vertices
// a turned copy kept put it back, so the copy is handed out and traced.
TEST(SelfCheckCommands, AnUnevenBallIsHandedOutAndTracedTurned) {
  const std::string original = temp_file("uneven_ball.obj").string();
  write_mesh(original, uneven_ball(4));
  const std::string marked = temp_file("uneven_ball_marked.obj").string();
  const test::CliRun embed = test::run_cli("embed " + original + " " + marked + " --key k1 --payload 0123456789abcdef");
  ASSERT_EQ(embed.exit_status, 0) << embed.out;
  EXPECT_NE(embed.out.find("moved"), std::string::npos) << "the copy was not read back turned: " << embed.out;
  const std::string turned = temp_file("uneven_ball_turned.ply").string();
  const Mesh copy = read_mesh(marked).mesh;
  write_mesh(turned, reorder(transform_mesh(copy, random_similarity(copy, 9)), 9));
  const test::CliRun detect = test::run_cli("detect " + turned + " --record " +
                                            test::record_of(marked, "0123456789abcdef") + " --key k1 --json");
  ASSERT_EQ(detect.exit_status, 0) << detect.out;
  const nlohmann::json d = nlohmann::json::parse(detect.out);
  EXPECT_EQ(d["payload"], "0123456789abcdef");
  EXPECT_EQ(d["ber"], 0.0);
}

// Faces wound inward, and every face stored twice (once per side): the copy reads back as the
// outward, single-sided original's does.
TEST(EmbedRoundTrip, InwardAndDoubleSidedMeshesReadBack) {
  const Mesh& creature = test::procedural_mesh("creature");
  for (const auto& [name, mesh] : {std::pair{"inward.obj", test::wound_inward(creature)},
                                   std::pair{"double_sided.obj", test::double_sided(creature)}}) {
    const std::string original = temp_file(name).string(), marked = temp_file(std::string("marked_") + name).string();
    write_mesh(original, mesh);
    const test::CliRun embed =
        test::run_cli("embed " + original + " " + marked + " --key k1 --payload 0123456789abcdef --json");
    ASSERT_EQ(embed.exit_status, 0) << embed.out;
    EXPECT_TRUE(nlohmann::json::parse(embed.out)["verification"]["passed"].get<bool>()) << name;
    const test::CliRun detect = test::run_cli("detect " + marked + " --key k1 --record " +
                                              test::record_of(marked, "0123456789abcdef") + " --json");
    ASSERT_EQ(detect.exit_status, 0) << detect.out;
    const nlohmann::json d = nlohmann::json::parse(detect.out);
    EXPECT_EQ(d["payload"], "0123456789abcdef") << name;
    EXPECT_EQ(d["ber"], 0.0) << name;
  }
}

// A small mesh refuses 64 bits and names what it carries; its 16-bit copy is then read without
// --bits or a record (every length it could carry is read, the p-value charged for them).
TEST(EmbedRoundTrip, ASmallMeshNamesItsCapacityAndItsShortCopyIsReadWithoutOptions) {
  const std::string original = test::procedural_file("torus_small").string();
  const std::string marked = temp_file("torus_small_marked.obj").string();
  const test::CliRun refused =
      test::run_cli("embed " + original + " " + marked + " --key k1 --payload 0123456789abcdef", true);
  ASSERT_EQ(refused.exit_status, 2) << refused.out;
  EXPECT_NE(refused.out.find("it carries at most"), std::string::npos) << refused.out;
  ASSERT_EQ(test::run_cli("embed " + original + " " + marked + " --key k1 --payload c0de --quiet").exit_status, 0);
  const test::CliRun detect = test::run_cli("detect " + marked + " --original " + original + " --key k1 --json");
  ASSERT_EQ(detect.exit_status, 0) << detect.out;
  const nlohmann::json d = nlohmann::json::parse(detect.out);
  EXPECT_EQ(d["payload"], "c0de") << d.dump();
  EXPECT_TRUE(d["detected"].get<bool>());
}

// "Not found" is an answer, not an error: exit 1 (as trace and the daemon's detect), the JSON printed.
TEST(EmbedAndDetectCommands, UnmarkedMeshExitsOneWithDetectedFalseAndNullBer) {
  const std::string original = test::procedural_file("creature").string();
  const test::CliRun detect = test::run_cli("detect " + original + " --original " + original + " --key k1 --json");
  ASSERT_EQ(detect.exit_status, 1);
  const nlohmann::json d = nlohmann::json::parse(detect.out);
  EXPECT_EQ(d["detected"], false);
  EXPECT_TRUE(d["ber"].is_null());
}

TEST(EmbedAndDetectCommands, InvalidMeshIsRefusedWithTheValidationMessage) {
  const auto tiny = temp_file("tiny.obj");
  write_mesh(tiny.string(), test::cube());
  const test::CliRun run =
      test::run_cli("embed " + tiny.string() + " " + temp_file("x.obj").string() + " --key k --payload ab", true);
  EXPECT_NE(run.exit_status, 0);
  EXPECT_NE(run.out.find("at least 100"), std::string::npos) << run.out;
  EXPECT_FALSE(std::filesystem::exists(temp_file("x.obj")));
}

TEST(EmbedRoundTrip, AMeshWithHolesIsMarkedWithItsHolesClosedVirtuallyAndSaysSo) {
  const auto original = temp_file("holes.obj"), marked = temp_file("holes_marked.obj");
  write_mesh(original, test::procedural_mesh("creature_holes"));
  const test::CliRun embed =
      test::run_cli("embed " + original.string() + " " + marked.string() + " --key k --payload 0123456789abcdef", true);
  ASSERT_EQ(embed.exit_status, 0) << embed.out;
  EXPECT_NE(embed.out.find("holes closed for the parameterization"), std::string::npos) << embed.out;
  const test::CliRun detect = test::run_cli("detect " + marked.string() + " --original " + original.string() +
                                            " --key k --expect 0123456789abcdef --json");
  const nlohmann::json j = nlohmann::json::parse(detect.out);
  EXPECT_TRUE(j["detected"].get<bool>());
  EXPECT_EQ(j["ber"].get<double>(), 0.0);
}

TEST(EmbedAndDetectCommands, BadPayloadIsAClearError) {
  const test::CliRun run = test::run_cli("embed " + test::procedural_file("creature").string() + " " +
                                             temp_file("y.obj").string() + " --key k --payload 12xz",
                                         true);
  EXPECT_EQ(run.exit_status, 2);
  EXPECT_NE(run.out.find("hex"), std::string::npos) << run.out;
}

}  // namespace
}  // namespace meshmark

namespace meshmark::test {
namespace {

// Parallel loops write only their own outputs: one thread or several, the same bytes.
TEST(ThreadCount, SphereEmbedAndDetectAreTheSameOnOneThreadAndOnSeveral) {
  const auto dir = std::filesystem::temp_directory_path() / "meshmark-threads-test";
  std::filesystem::create_directories(dir);
  const std::string mesh = procedural_file("creature").string();
  for (const char* threads : {"1", "4"}) {
    const std::string env = std::string("MESHMARK_THREADS=") + threads + " ";
    const std::string suffix = std::string("-") + threads + ".ply";
    ASSERT_EQ(std::system((env + test::cli_program() + " sphere " + mesh + " --out " +
                           (dir / ("sphere" + suffix)).string() + " > /dev/null")
                              .c_str()),
              0);
    ASSERT_EQ(std::system((env + test::cli_program() + " embed " + mesh + " " + (dir / ("marked" + suffix)).string() +
                           " --key k --payload 0123456789abcdef > /dev/null")
                              .c_str()),
              0);
  }
  // A larger mesh's descent passes move thousands of vertices of a colour at once: in parallel.
  const std::string large = procedural_file("creature_large").string();
  for (const char* threads : {"1", "4"})
    ASSERT_EQ(std::system((std::string("MESHMARK_THREADS=") + threads + " " + test::cli_program() + " sphere " + large +
                           " --out " + (dir / (std::string("large-") + threads + ".ply")).string() + " > /dev/null")
                              .c_str()),
              0);
  for (const char* name : {"sphere", "marked", "large"})
    EXPECT_EQ(file_bytes((dir / (std::string(name) + "-1.ply")).string()),
              file_bytes((dir / (std::string(name) + "-4.ply")).string()))
        << name;
  // Detection too: every figure it reports but the timings.
  std::vector<nlohmann::json> detections;
  for (const char* threads : {"1", "4"}) {
    const CliRun run = run_cli("detect " + (dir / "marked-1.ply").string() + " --original " + mesh + " --key k --json",
                               false, std::string("MESHMARK_THREADS=") + threads);
    ASSERT_EQ(run.exit_status, 0) << run.out;
    nlohmann::json j = nlohmann::json::parse(run.out);
    j.erase("seconds");
    detections.push_back(j);
  }
  EXPECT_EQ(detections[0], detections[1]);
  EXPECT_TRUE(detections[0].value("detected", false));
  std::filesystem::remove_all(dir);
}

// --threads and MESHMARK_THREADS say how many; a count that is not one is refused before any work.
TEST(ThreadCount, AThreadCountThatIsNotOneIsRefusedWithItsName) {
  const std::string mesh = procedural_file("creature").string();
  const CliRun flag = run_cli("embed " + mesh + " /tmp/never.obj --key k --payload 01 --threads 65", true);
  EXPECT_EQ(flag.exit_status, 2);
  EXPECT_NE(flag.out.find("--threads"), std::string::npos) << flag.out;
  const CliRun env = run_cli("detect " + mesh + " --original " + mesh + " --key k", true, "MESHMARK_THREADS=many");
  EXPECT_EQ(env.exit_status, 2);
  EXPECT_NE(env.out.find("--threads"), std::string::npos) << env.out;
  EXPECT_FALSE(std::filesystem::exists("/tmp/never.obj"));
  const CliRun bench = run_cli("bench --threads 99 --runs 1", true);
  EXPECT_EQ(bench.exit_status, 2);
  EXPECT_NE(bench.out.find("--threads"), std::string::npos) << bench.out;
}

// The bumps are built in parallel, one centre per task: the same bytes on any thread count.
TEST(ThreadCount, BumpEmbedIsTheSameOnOneThreadAndOnSeveral) {
  const auto dir = std::filesystem::temp_directory_path() / "meshmark-threads-bumps-test";
  std::filesystem::create_directories(dir);
  const std::string mesh = procedural_file("torus", "off").string();
  for (const char* threads : {"1", "4"})
    ASSERT_EQ(std::system((std::string("MESHMARK_THREADS=") + threads + " " + test::cli_program() + " embed " + mesh +
                           " " + (dir / (std::string("marked-") + threads + ".off")).string() +
                           " --key k --payload 0123456789abcdef > /dev/null")
                              .c_str()),
              0);
  EXPECT_EQ(file_bytes((dir / "marked-1.off").string()), file_bytes((dir / "marked-4.off").string()));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace meshmark::test

namespace meshmark {
namespace {

// Runs a shell command under a pseudo-terminal (`script`, util-linux) and returns what it printed.
std::string on_a_terminal(const std::string& command) {
  FILE* pipe = popen(("script -qec '" + command + "' /dev/null").c_str(), "r");
  if (!pipe) return "";
  std::string out;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
  pclose(pipe);
  return out;
}

TEST(LocalProgress, ShowsStagesOnATerminalAndNothingInAPipeOrWithQuiet) {
  const std::string mesh = test::procedural_file("creature").string();
  const test::CliRun piped = test::run_cli("sphere " + mesh, true);
  EXPECT_EQ(piped.exit_status, 0);
  EXPECT_EQ(piped.out.find('\r'), std::string::npos) << "no progress when standard error is not a terminal";
  EXPECT_NE(on_a_terminal(std::string(test::cli_program()) + " sphere " + mesh).find("sphere: parameterize"),
            std::string::npos);
  EXPECT_EQ(on_a_terminal(std::string(test::cli_program()) + " sphere --quiet " + mesh).find("parameterize"),
            std::string::npos);
}

}  // namespace
}  // namespace meshmark

namespace meshmark {
namespace {

// A copy made with a 32-bit payload on the octahedral grid: detection needed those options again.
TEST(CopyRecordCommands, DetectWithTheRecordReadsACopyMadeWithOtherSettings) {
  const std::string original = test::procedural_file("creature").string();
  const std::string marked = temp_file("creature_octa.ply").string();
  ASSERT_EQ(test::run_cli("embed " + original + " " + marked + " --key k2 --payload c0ffee15 --base octa --quiet")
                .exit_status,
            0);
  const std::string record = test::record_of(marked, "c0ffee15");
  ASSERT_TRUE(std::filesystem::exists(record));

  const auto with_record =
      test::run_cli("detect " + marked + " --original " + original + " --key k2 --record " + record + " --json");
  ASSERT_EQ(with_record.exit_status, 0) << with_record.out;
  const nlohmann::json d = nlohmann::json::parse(with_record.out);
  EXPECT_TRUE(d.value("detected", false));
  EXPECT_EQ(d.value("ber", 1.0), 0.0);
  EXPECT_TRUE(d["record"].value("original_matches", false));

  const auto without = test::run_cli("detect " + marked + " --original " + original + " --key k2 --json");
  EXPECT_FALSE(nlohmann::json::parse(without.out).value("detected", true))
      << "the defaults are not what it was made with";

  const auto contradiction =
      test::run_cli("detect " + marked + " --original " + original + " --key k2 --base tetra --record " + record, true);
  EXPECT_EQ(contradiction.exit_status, 2);
  EXPECT_NE(contradiction.out.find("contradicts the copy's record"), std::string::npos) << contradiction.out;
}

// The procedural `shape` as a modelling tool re-exports it: vertices and faces renumbered, turned
// and moved, then written with 6 significant digits.
std::string reexported(const std::string& shape) {
  const std::string moved = temp_file("moved_" + shape + ".off").string();
  EXPECT_EQ(test::run_cli("attack chain " + test::procedural_file(shape).string() + " " + moved +
                          " --steps 'reorder | similarity | digits digits=6'")
                .exit_status,
            0);
  return moved;
}

// The record stores the original as prepared: an original re-saved with 6 significant digits,
// its vertices and faces reordered and rotated, still reads the copy, and is named for what it is.
void expect_read_against_a_resaved_original(const std::string& shape) {
  const std::string original = test::procedural_file(shape).string();
  const std::string mesh_name = shape + ".obj";
  const std::string marked = temp_file("resaved_" + mesh_name + ".ply").string();
  ASSERT_EQ(
      test::run_cli("embed " + original + " " + marked + " --key k3 --payload 0123456789abcdef --quiet").exit_status,
      0);
  const auto run = test::run_cli("detect " + marked + " --original " + reexported(shape) + " --key k3 --record " +
                                 test::record_of(marked, "0123456789abcdef") + " --json");
  ASSERT_EQ(run.exit_status, 0) << run.out;
  const nlohmann::json d = nlohmann::json::parse(run.out);
  EXPECT_EQ(d.value("ber", 1.0), 0.0) << mesh_name;
  EXPECT_TRUE(d.value("detected", false)) << mesh_name;
  EXPECT_TRUE(d["record"].value("original_matches", false)) << d["record"].dump();
  EXPECT_NE(d["record"].value("note", "").find("re-saved, reordered or moved"), std::string::npos)
      << d["record"].dump();
}

TEST(CopyRecordCommands, AResavedReorderedRotatedOriginalStillReadsTheCopy) {
  expect_read_against_a_resaved_original("creature");
  expect_read_against_a_resaved_original("creature_large");
}

// Without the copy's record, a re-exported master is found in the records folder as the original
// stored when the copy was made, and the copy reads against it, in either scheme. Where the folder
// does not hold it, the master's own preparation (its sphere map follows the file's exact numbers)
// cannot read the copy.
TEST(CopyRecordCommands, AReExportedOriginalReadsTheCopyWithoutItsRecord) {
  const std::string master = reexported("creature");
  for (const std::string scheme : {"spread", "paper"}) {
    const std::string marked = temp_file("reexported_" + scheme + ".ply").string();
    ASSERT_EQ(test::run_cli("embed " + test::procedural_file("creature").string() + " " + marked +
                            " --key k5 --payload 0123456789abcdef --quiet --scheme " + scheme)
                  .exit_status,
              0);
    const std::string detect =
        "detect " + marked + " --original " + master + " --key k5 --expect 0123456789abcdef --json --scheme " + scheme;
    const auto run = test::run_cli(detect);
    ASSERT_EQ(run.exit_status, 0) << run.out;
    const nlohmann::json d = nlohmann::json::parse(run.out);
    EXPECT_EQ(d.value("ber", 1.0), 0.0) << scheme;
    EXPECT_NE(d["stored_original"].value("note", "").find("re-saved, reordered or moved"), std::string::npos)
        << d.dump();
    const auto elsewhere = test::run_cli(detect + " --records " + temp_file("no_records").string());
    EXPECT_FALSE(nlohmann::json::parse(elsewhere.out).value("detected", true)) << scheme;
  }
}

TEST(CopyRecordCommands, AnotherOriginalThanTheRecordedOneIsSaidInWords) {
  const std::string marked = temp_file("creature_rec.ply").string();
  ASSERT_EQ(test::run_cli("embed " + test::procedural_file("creature").string() + " " + marked +
                          " --key k4 --payload 0123456789abcdef --quiet")
                .exit_status,
            0);
  const auto run =
      test::run_cli("detect " + marked + " --original " + test::procedural_file("creature_large").string() +
                    " --key k4 --record " + test::record_of(marked, "0123456789abcdef") + " --json");
  const nlohmann::json d = nlohmann::json::parse(run.out);
  EXPECT_FALSE(d["record"].value("original_matches", true));
  EXPECT_NE(d["record"].value("note", "").find("is not the original the record names"), std::string::npos) << d.dump();
  EXPECT_TRUE(d.value("detected", false)) << "read against the recorded original all the same";
}

TEST(CopyRecordCommands, EmbedWithNoRecordWritesNone) {
  const std::string marked = temp_file("creature_norecord.ply").string();
  ASSERT_EQ(test::run_cli("embed " + test::procedural_file("creature").string() + " " + marked +
                          " --key k --payload 01234567 --no-record --quiet")
                .exit_status,
            0);
  EXPECT_FALSE(std::filesystem::exists(test::record_of(marked, "01234567")));
}

// `trace` names the copy a suspect is among copies of one original, from their records alone.
TEST(TraceCommand, NamesTheCopyAHalvedSuspectWasMadeFromAmongItsSiblings) {
  const std::string original = test::procedural_file("creature").string();
  const std::string alice = temp_file("trace_alice.ply").string(), bob = temp_file("trace_bob.ply").string();
  ASSERT_EQ(
      test::run_cli("embed " + original + " " + alice + " --key kt --payload 0123456789abcdef --quiet").exit_status, 0);
  ASSERT_EQ(test::run_cli("embed " + original + " " + bob + " --key kt --payload fedcba9876543210 --quiet").exit_status,
            0);
  const std::string suspect = temp_file("trace_suspect.ply").string();
  ASSERT_EQ(test::run_cli("attack simplify " + bob + " " + suspect + " --keep 0.5").exit_status, 0);
  const auto run = test::run_cli("trace " + suspect + " " + test::record_of(alice, "0123456789abcdef") + " " +
                                 test::record_of(bob, "fedcba9876543210") + " --key kt --json");
  ASSERT_EQ(run.exit_status, 0) << run.out;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  ASSERT_TRUE(j["match"].is_object()) << run.out;
  EXPECT_EQ(j["match"]["payload"], "fedcba9876543210");
  EXPECT_EQ(j["ranked"].size(), 2u);
  EXPECT_LT(j["match"]["log10_p_value"].get<double>(), -6);
}

// A copy for each recipient in one command: one file and one record each, the record naming its
// recipient, every payload its own; trace then names the recipient of a leaked copy.
TEST(TraceCommand, ACopyPerRecipientIsTracedToItsRecipient) {
  const std::string original = test::procedural_file("creature").string();
  const auto out = temp_file("trace_batch"), records = temp_file("trace_batch_records");
  const auto made =
      test::run_cli("embed " + original + " " + out.string() + " --recipients alice,bob,'carol c' --key kb" +
                    " --records " + records.string() + " --quiet");
  ASSERT_EQ(made.exit_status, 0) << made.out;
  std::vector<std::string> record_files;
  std::set<std::string> payloads;
  for (const auto& e : std::filesystem::directory_iterator(records))
    if (e.path().string().ends_with(".record.json")) {
      record_files.push_back(e.path().string());
      payloads.insert(copy_record_from_json(nlohmann::json::parse(read_file_bytes(e.path(), 1 << 20))).payload);
    }
  ASSERT_EQ(record_files.size(), 3u) << made.out;
  EXPECT_EQ(payloads.size(), 3u);
  const auto bob = out / "creature-bob.obj";
  ASSERT_TRUE(std::filesystem::exists(out / "creature-carol c.obj")) << made.out;
  std::string all_records;
  for (const std::string& r : record_files) all_records += " '" + r + "'";
  const auto run = test::run_cli("trace " + bob.string() + all_records + " --key kb");
  ASSERT_EQ(run.exit_status, 0) << run.out;
  EXPECT_NE(run.out.find(": the copy given to \"bob\" (" + bob.string()), std::string::npos) << run.out;
  const auto mixed =
      test::run_cli("embed " + original + " " + out.string() + " --recipients dave --payload ab --key kb", true);
  EXPECT_EQ(mixed.exit_status, 2);
  EXPECT_NE(mixed.out.find("no --payload with it"), std::string::npos) << mixed.out;
}

// The copies of one command share their self-check's registration: the first is read moved and
// registered, and once that has found it, the next read their re-save in place.
TEST(TraceCommand, ACopyPerRecipientProvesRegistrationOnce) {
  const std::string original = test::procedural_file("creature").string();
  const auto out = temp_file("batch_proof"), records = temp_file("batch_proof_records");
  const auto made = test::run_cli("embed " + original + " " + out.string() + " --recipients ann,ben,cy --key kb" +
                                  " --records " + records.string() + " --quiet --json");
  ASSERT_EQ(made.exit_status, 0) << made.out;
  const auto count = [&](const std::string& text) {
    std::size_t n = 0;
    for (std::size_t at = made.out.find(text); at != std::string::npos; at = made.out.find(text, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("\"as written\""), 3u) << made.out;
  EXPECT_EQ(count("\"re-saved with 6 digits and moved\""), 1u) << made.out;
  EXPECT_EQ(count("\"re-saved with 6 digits\""), 2u) << made.out;
}

TEST(TraceCommand, TheUnmarkedOriginalMatchesNoCopyAndExitsOne) {
  const std::string original = test::procedural_file("creature").string();
  const std::string copy = temp_file("trace_only.ply").string();
  ASSERT_EQ(
      test::run_cli("embed " + original + " " + copy + " --key kt --payload 00ff00ff00ff00ff --quiet").exit_status, 0);
  const auto run = test::run_cli("trace " + original + " " + test::record_of(copy, "00ff00ff00ff00ff") + " --key kt");
  EXPECT_EQ(run.exit_status, 1) << run.out;
  EXPECT_NE(run.out.find("no watermark of this key found"), std::string::npos) << run.out;
}

TEST(TraceCommand, RecordsOfDifferentOriginalsAreRefusedBeforeAnyReading) {
  const std::string creature = temp_file("trace_creature.ply").string(), torus = temp_file("trace_torus.ply").string();
  ASSERT_EQ(test::run_cli("embed " + test::procedural_file("creature").string() + " " + creature +
                          " --key kt --payload 01234567 --quiet")
                .exit_status,
            0);
  ASSERT_EQ(test::run_cli("embed " + test::procedural_file("torus", "off").string() + " " + torus +
                          " --key kt --payload 01234567 --quiet")
                .exit_status,
            0);
  const auto run = test::run_cli("trace " + creature + " " + test::record_of(creature, "01234567") + " " +
                                     test::record_of(torus, "01234567") + " --key kt",
                                 true);
  EXPECT_EQ(run.exit_status, 2) << run.out;
  EXPECT_NE(run.out.find("trace the copies of each original separately"), std::string::npos) << run.out;
}

}  // namespace
}  // namespace meshmark
