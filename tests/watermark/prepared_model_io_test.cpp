#include "core/watermark/prepared_model_io.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "core/mesh/mesh_report_io.hpp"
#include "core/util/keyed_random.hpp"
#include "core/watermark/detect_stages.hpp"
#include "core/watermark/nuisance_fields.hpp"
#include "core/watermark/watermark.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

const PreparedModel& creature() {
  static const PreparedModel m = prepare_model(test::procedural_mesh("creature"));
  return m;
}

const std::string& spot_bytes() {
  static const std::string bytes = serialize_prepared_model(creature());
  return bytes;
}

TEST(PreparedModelIo, RoundTripGivesTheSameWatermarkedMesh) {
  const PreparedModel loaded = deserialize_prepared_model(spot_bytes(), creature().mesh);
  const Bits payload = bits_from_hex("0123456789abcdef");
  const EmbedResult a = embed_watermark(creature(), "key", payload);
  const EmbedResult b = embed_watermark(loaded, "key", payload);
  EXPECT_EQ((a.mesh.V - b.mesh.V).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(loaded.level(), creature().level());
  EXPECT_EQ(loaded.digest, creature().digest);
}

TEST(PreparedModelIo, RoundTripKeepsTheParameterization) {
  const PreparedModel loaded = deserialize_prepared_model(spot_bytes(), creature().mesh);
  EXPECT_EQ((loaded.param.S - creature().param.S).cwiseAbs().maxCoeff(), 0.0);
}

// Detection's nuisance fields come with the file (made at writing if no detection had made them),
// exactly as a fresh model makes them: a copy reads the same from either.
TEST(PreparedModelIo, RoundTripCarriesTheNuisanceFieldsExactly) {
  const PreparedModel fresh = prepare_model(test::procedural_mesh("creature"));
  const PreparedModel loaded = deserialize_prepared_model(serialize_prepared_model(fresh), fresh.mesh);
  const Eigen::MatrixXd computed = nuisance_fields(fresh.mesh, fresh.normals, 1);
  std::call_once(loaded.nuisance->once, [] { FAIL() << "the loaded model had no nuisance fields"; });
  ASSERT_EQ(loaded.nuisance->value.rows(), computed.rows());
  EXPECT_EQ((loaded.nuisance->value - computed).cwiseAbs().maxCoeff(), 0.0);
}

// Every basis survives the store: the same marked mesh from the loaded model as from the fresh one.
TEST(PreparedModelIo, FilledSphereAndBumpModelsRoundTrip) {
  for (const char* name : {"creature_holes", "pinched"}) {
    const PreparedModel fresh = prepare_model(test::procedural_mesh(name));
    EXPECT_NE(fresh.basis, MeshBasis::sphere) << name;
    const PreparedModel loaded = deserialize_prepared_model(serialize_prepared_model(fresh), fresh.mesh);
    EXPECT_EQ(loaded.basis, fresh.basis) << name;
    EXPECT_EQ(loaded.basis_reason, fresh.basis_reason) << name;
    EXPECT_TRUE(loaded.report == fresh.report) << name;  // stored, not validated again
    const Bits payload = bits_from_hex("0123456789abcdef");
    const EmbedResult a = embed_watermark(fresh, "key", payload);
    const EmbedResult b = embed_watermark(loaded, "key", payload);
    EXPECT_EQ((a.mesh.V - b.mesh.V).cwiseAbs().maxCoeff(), 0.0) << name;
  }
}

// A version 5 file (written before the report was stored: the same bytes without it) still loads
// and validates its mesh again, to the same report.
TEST(PreparedModelIo, AVersionFiveFileLoadsAndValidatesItsMesh) {
  const std::string v6 = spot_bytes();
  constexpr std::size_t kMagicBytes = sizeof("MESHMARK-PREPARED"), kVersionAt = kMagicBytes;
  BinaryReader digest(std::string_view(v6).substr(kVersionAt + 4));
  const std::size_t report_at = kVersionAt + 4 + 8 + digest.get_string().size();
  BinaryWriter report;
  put_mesh_report(report, creature().report);
  std::string v5 = v6.substr(0, v6.size() - 32);
  v5.erase(report_at, report.bytes().size());
  const std::uint32_t five = 5;
  std::memcpy(v5.data() + kVersionAt, &five, 4);
  const auto checksum = sha256(v5);
  v5.append(reinterpret_cast<const char*>(checksum.data()), checksum.size());
  const PreparedModel loaded = deserialize_prepared_model(v5, creature().mesh);
  EXPECT_TRUE(loaded.report == creature().report);
  const Bits payload = bits_from_hex("0123456789abcdef");
  EXPECT_EQ((embed_watermark(loaded, "key", payload).mesh.V - embed_watermark(creature(), "key", payload).mesh.V)
                .cwiseAbs()
                .maxCoeff(),
            0.0);
}

TEST(PreparedModelIo, AFlippedByteIsDetected) {
  std::string damaged = spot_bytes();
  damaged[damaged.size() / 2] ^= 0x10;
  EXPECT_THROW(deserialize_prepared_model(damaged, creature().mesh), std::runtime_error);
}

TEST(PreparedModelIo, ATruncatedFileIsDetected) {
  for (std::size_t keep : {std::size_t{0}, std::size_t{10}, spot_bytes().size() / 3, spot_bytes().size() - 1})
    EXPECT_THROW(deserialize_prepared_model(spot_bytes().substr(0, keep), creature().mesh), std::runtime_error) << keep;
}

TEST(PreparedModelIo, AFileOfAnotherMeshIsRefused) {
  Mesh other = creature().mesh;
  other.V(0, 0) += 1e-3;
  EXPECT_THROW(deserialize_prepared_model(spot_bytes(), other), std::runtime_error);
}

TEST(JobControl, ACanceledEmbedStopsWithCanceled) {
  std::atomic<bool> cancel{true};
  JobControl control;
  control.cancel = &cancel;
  EXPECT_THROW(embed_watermark(creature(), "key", bits_from_hex("ab"), {}, &control), Canceled);
}

TEST(JobControl, APastDeadlineStopsWithTimeLimitExceeded) {
  JobControl control;
  control.deadline = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  EXPECT_THROW(detect_watermark(creature(), creature().mesh, "key", {}, nullptr, &control), TimeLimitExceeded);
}

TEST(JobControl, DetectionReportsItsStagesWithGrowingProgress) {
  std::vector<std::string> stages;
  std::vector<double> progress;
  JobControl control;
  control.report = [&](const std::string& stage, double p) {
    stages.push_back(stage);
    progress.push_back(p);
  };
  detect_watermark(creature(), creature().mesh, "key", {}, nullptr, &control);
  // The alignment, each candidate registration measured, then the readings of them all: the
  // matched filter's and, since it does not decide on an unmarked mesh, every estimate's.
  ASSERT_GE(stages.size(), 4u);
  EXPECT_EQ(stages[0], detect_stage::align);
  const auto reads = static_cast<std::size_t>(std::count(stages.begin(), stages.end(), detect_stage::read));
  ASSERT_GE(reads, 1u);
  ASSERT_EQ(stages.size(), 1 + reads + 2 * 2 * reads);
  for (std::size_t i = 1; i <= reads; ++i) EXPECT_EQ(stages[i], detect_stage::read);
  for (std::size_t i = 1 + reads; i < stages.size(); i += 2)
    EXPECT_EQ((std::vector<std::string>(stages.begin() + i, stages.begin() + i + 2)),
              (std::vector<std::string>{detect_stage::estimate, detect_stage::decode}));
  for (std::size_t i = 1; i < progress.size(); ++i) EXPECT_GE(progress[i], progress[i - 1]) << stages[i];
  EXPECT_LT(progress.back(), 1.0);
}

TEST(JobControl, EmbeddingReportsItsStagesForBothSchemes) {
  for (const Scheme scheme : {Scheme::spread, Scheme::paper}) {
    std::vector<std::string> stages;
    JobControl control;
    control.report = [&](const std::string& stage, double) { stages.push_back(stage); };
    WatermarkOptions options;
    options.scheme = scheme;
    embed_watermark(creature(), "key", bits_from_hex("ab"), options, &control);
    EXPECT_EQ(stages, (std::vector<std::string>{embed_stage::plan, embed_stage::synthesis, embed_stage::apply}));
  }
}

TEST(Candidates, TheEmbeddedPayloadHasTheSmallestPValue) {
  const Bits payload = bits_from_hex("0123456789abcdef");
  const EmbedResult e = embed_watermark(creature(), "key", payload);
  DetectOptions options;
  options.candidates = {bits_from_hex("fedcba9876543210"), payload, bits_from_hex("0123456789abcdee")};
  const DetectResult r = detect_watermark(creature(), e.mesh, "key", options);
  ASSERT_EQ(r.candidate_log10_p.size(), 3u);
  EXPECT_LT(r.candidate_log10_p[1], -6);
  EXPECT_LT(r.candidate_log10_p[1], r.candidate_log10_p[0]);
  EXPECT_LT(r.candidate_log10_p[1], r.candidate_log10_p[2]);
  EXPECT_GT(r.candidate_log10_p[0], -3);  // an unrelated payload does not match
}

}  // namespace
}  // namespace meshmark
