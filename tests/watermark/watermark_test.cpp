#include "core/watermark/watermark.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/attacks/attack_registry.hpp"
#include "core/attacks/similarity_transform.hpp"
#include "core/attacks/subdivide.hpp"
#include "core/watermark/carrier_estimate.hpp"
#include "core/watermark/vertex_offsets.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

const PreparedModel& large_creature_model() {
  static const PreparedModel m = prepare_model(test::procedural_mesh("creature_large"));
  return m;
}

// For what is refused before any geometry is touched: a prepared model that costs nothing.
const PreparedModel& low_poly_model() {
  static const PreparedModel m = prepare_model(test::creature(2));
  return m;
}

class PaperScheme : public ::testing::TestWithParam<WaveletType> {
 protected:
  // The creature marked by the paper's rule with this wavelet, attacked by `chain` (none when
  // empty) and read through registration.
  static DetectResult mark_attack_and_read(const std::string& chain) {
    WatermarkOptions options;
    options.scheme = Scheme::paper;
    options.wavelet = GetParam();
    const Bits payload = bits_from_hex("0123456789abcdef");
    const EmbedResult e = embed_watermark(large_creature_model(), "paper key", payload, options);
    EXPECT_TRUE(e.mesh.F == large_creature_model().mesh.F);
    const Mesh copy = chain.empty() ? e.mesh : apply_attack_chain(e.mesh, parse_attack_chain(chain), 3);
    DetectOptions d;
    d.watermark = options;
    d.expected = payload;
    return detect_watermark(large_creature_model(), copy, "paper key", d);
  }
};

TEST_P(PaperScheme, EmbedsAndDetectsWithoutErrorsUnattacked) {
  const DetectResult r = mark_attack_and_read("");
  EXPECT_EQ(r.ber, 0.0);
  EXPECT_TRUE(r.detected);
  EXPECT_GE(r.raw_bit_error_rate, 0.0);
  EXPECT_LT(r.raw_bit_error_rate, 0.04);
}

// Jin et al.'s Table 1 reads 1e-4 of the carriers wrong after reordering: with the copy's vertices
// corresponding to the original's, the whole offset is read (not only its normal part, which
// reads 0.1-0.34 of them wrong). Coefficients whose hat functions the original's vertices hardly
// see are no carriers (grid_coverage.hpp): on this small mesh they were 2.1 % of the carriers
// read wrong with the linear wavelet, 0.34 % with its lifting.
TEST_P(PaperScheme, AReorderedAndMovedCopyReadsTheCarriersAsThePaperDoes) {
  const DetectResult r = mark_attack_and_read("reorder | similarity");
  EXPECT_EQ(r.ber, 0.0);
  EXPECT_TRUE(r.detected);
  EXPECT_LE(r.raw_bit_error_rate, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Wavelets, PaperScheme, ::testing::Values(WaveletType::linear, WaveletType::linear_lifting));

// A copy with the original's vertices in their order reads in place as through registration:
// the same payload, no bit wrong, a decision; a copy with other vertices is refused.
TEST(Watermark, ACopyReadInPlaceGivesItsPayload) {
  const Bits payload = bits_from_hex("0123456789abcdef");
  const EmbedResult e = embed_watermark(large_creature_model(), "in place", payload, {});
  DetectOptions d;
  d.expected = payload;
  const DetectResult r = detect_in_place(large_creature_model(), e.mesh, "in place", d);
  EXPECT_EQ(r.ber, 0.0);
  EXPECT_TRUE(r.detected);
  ASSERT_TRUE(r.payload.has_value());
  EXPECT_EQ(*r.payload, payload);
  const DetectResult wrong_key = detect_in_place(large_creature_model(), e.mesh, "another key", d);
  EXPECT_FALSE(wrong_key.detected);
  const DetectResult unmarked = detect_in_place(large_creature_model(), large_creature_model().mesh, "in place", d);
  EXPECT_FALSE(unmarked.detected);
  EXPECT_THROW(detect_in_place(large_creature_model(), test::procedural_mesh("creature"), "in place", d),
               std::invalid_argument);
}

// A copy that kept the original's vertices in their order, registered by its shape (the order
// not tried, as the embed's self-check registers its moved copy), reads at its vertices as in
// place. On a dense mesh the mark moves vertices further than half an edge, where mutual nearest
// vertices pair too few and the reading fell to projection: weaker, and at millions of vertices
// half the self-check's time.
TEST(Watermark, ACopyInItsOrderRegisteredByItsShapeReadsAtItsVerticesOnADenseMesh) {
  static const PreparedModel model =
      prepare_model(subdivide(test::procedural_mesh("creature_large"), SubdivisionScheme::loop));
  const Bits payload = bits_from_hex("0123456789abcdef");
  WatermarkOptions options;
  options.strength_percent = 0.1;  // twice the default: the mark moves one vertex in eight beyond half an edge
  const EmbedResult e = embed_watermark(model, "dense", payload, options);
  const double edge = median_edge_length(model.mesh);
  const Eigen::ArrayXd moved_by = (e.mesh.V - model.mesh.V).rowwise().norm().array();
  ASSERT_GT((moved_by > 0.5 * edge).count(), moved_by.size() / 10);
  ASSERT_FALSE(corresponding_offsets(model.mesh, e.mesh, e.mesh.V, edge).has_value());
  DetectOptions d;
  d.watermark = options;
  d.expected = payload;
  d.align.try_order = false;
  const DetectResult in_place = detect_in_place(model, e.mesh, "dense", d);
  const DetectResult r = detect_watermark(model, transform_mesh(e.mesh, random_similarity(e.mesh, 5)), "dense", d);
  EXPECT_FALSE(r.alignment.by_order());
  EXPECT_EQ(r.ber, 0.0);
  EXPECT_TRUE(r.detected);
  EXPECT_EQ(r.missing, 0u);
  EXPECT_NEAR(r.z_score, in_place.z_score, 1e-3 * in_place.z_score);
}

// A reading with the matched filter alone pays in its bound for every estimate the detector
// tries when told to: the same statistic, a bound exactly as large as the detector's would be.
TEST(Watermark, AQuickReadingPaysForEveryEstimateTheDetectorTries) {
  const Bits payload = bits_from_hex("0123456789abcdef");
  const EmbedResult e = embed_watermark(large_creature_model(), "quick", payload, {});
  DetectOptions quick;
  quick.expected = payload;
  quick.estimate.spread_regularizations = {0.0};
  const DetectResult unpaid = detect_in_place(large_creature_model(), e.mesh, "quick", quick);
  quick.estimate.charged_estimates = DetectOptions{}.estimate.spread_regularizations.size();
  const DetectResult paid = detect_in_place(large_creature_model(), e.mesh, "quick", quick);
  EXPECT_EQ(paid.z_score, unpaid.z_score);
  EXPECT_GT(paid.blind_log10_p_value, unpaid.blind_log10_p_value);
  EXPECT_NEAR(paid.blind_log10_p_value - unpaid.blind_log10_p_value,
              std::log10(2.0) * (bits_for_tries(2 * 3) - bits_for_tries(2 * 1)), 1e-9);
  EXPECT_TRUE(paid.detected);
  EXPECT_EQ(paid.ber, 0.0);
}

// The detector reads with the matched filter first and stops there only when that decides: a copy
// reads as the matched filter alone paid for every estimate reads it, while a mesh that is not a
// copy (the unmarked original, a wrong key) gets the whole detector's answer, bit for bit.
TEST(Watermark, TheMatchedFilterDecidesAloneOnlyWhenItDetectsTheWholeDetectorStillJudgesTheRest) {
  const Bits payload = bits_from_hex("0123456789abcdef");
  const PreparedModel& model = large_creature_model();
  const Mesh moved = apply_attack_chain(embed_watermark(model, "first", payload, {}).mesh,
                                        parse_attack_chain("noise amplitude=0.05 | similarity"), 5);
  DetectOptions first, whole, alone;
  first.expected = whole.expected = alone.expected = payload;
  whole.estimate.matched_first = false;
  alone.estimate.spread_regularizations = {0.0};
  alone.estimate.charged_estimates = DetectOptions{}.estimate.spread_regularizations.size();
  const DetectResult read_first = detect_watermark(model, moved, "first", first);
  const DetectResult read_alone = detect_watermark(model, moved, "first", alone);
  EXPECT_TRUE(read_first.detected);
  EXPECT_EQ(read_first.ber, 0.0);
  EXPECT_EQ(read_first.z_score, read_alone.z_score);
  EXPECT_EQ(read_first.log10_p_value, read_alone.log10_p_value);
  EXPECT_GE(read_first.log10_p_value, detect_watermark(model, moved, "first", whole).log10_p_value);
  // Passing the threshold by less than a million-fold (what later charges may take), it does not
  // decide alone: the answer is the whole detector's.
  DetectOptions near = first, near_whole = whole;
  near.false_alarm = near_whole.false_alarm = std::pow(10.0, read_alone.log10_p_value + 3);
  const DetectResult read_near = detect_watermark(model, moved, "first", near);
  EXPECT_EQ(read_near.log10_p_value, detect_watermark(model, moved, "first", near_whole).log10_p_value);
  EXPECT_LT(read_near.log10_p_value, read_alone.log10_p_value);
  for (const auto& [suspect, key] : {std::pair{&model.mesh, "first"}, std::pair{&moved, "another"}}) {
    const DetectResult a = detect_watermark(model, *suspect, key, first),
                       b = detect_watermark(model, *suspect, key, whole);
    EXPECT_FALSE(a.detected) << key;
    EXPECT_EQ(a.z_score, b.z_score) << key;
    EXPECT_EQ(a.log10_p_value, b.log10_p_value) << key;
  }
}

TEST(Watermark, RefusesAMeshThatCannotBeWatermarkedWithTheValidationMessage) {
  try {
    prepare_model(test::cube());
    FAIL() << "a cube (8 vertices) was accepted";
  } catch (const ModelRefused& e) {
    EXPECT_NE(std::string(e.what()).find("at least 100"), std::string::npos) << e.what();
    EXPECT_FALSE(e.report.valid);
  }
}

// Two parts, the payload spread over both: a copy with one part cropped away reads the same
// payload from the other (the missing part's carriers are erasures, not errors).
TEST(Watermark, TwoPartsCroppedToOneStillDecode) {
  const Mesh& creature = test::procedural_mesh("creature");
  const Eigen::Index n = creature.V.rows();
  const PreparedModel model = prepare_model(test::side_by_side(creature, creature));
  ASSERT_EQ(model.basis, MeshBasis::bumps);
  EXPECT_EQ(model.bumps->marked_components, 2u);
  const Bits payload = bits_from_hex("0123456789abcdef");
  const EmbedResult e = embed_watermark(model, "two parts", payload, {});
  DetectOptions d;
  d.expected = payload;
  const DetectResult whole = detect_watermark(model, e.mesh, "two parts", d);
  EXPECT_EQ(whole.ber, 0.0);
  for (const Eigen::Index first : {Eigen::Index{0}, n}) {  // keep either part
    const Mesh part{e.mesh.V.middleRows(first, n), creature.F};
    const DetectResult r = detect_watermark(model, part, "two parts", d);
    EXPECT_EQ(r.ber, 0.0) << "part at " << first;
    EXPECT_TRUE(r.detected) << "part at " << first << ": log10 p " << r.log10_p_value;
    EXPECT_GT(r.log10_p_value, whole.log10_p_value);  // half the evidence
  }
}

TEST(Watermark, ThePaperSchemeRefusesABumpBasisWithTheReason) {
  const PreparedModel torus = prepare_model(test::procedural_mesh("torus"));
  ASSERT_EQ(torus.basis, MeshBasis::bumps);
  WatermarkOptions paper;
  paper.scheme = Scheme::paper;
  try {
    embed_watermark(torus, "k", bits_from_hex("ab"), paper);
    FAIL() << "the paper's scheme ran on bumps";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("spread"), std::string::npos) << e.what();
  }
}

TEST(Watermark, RefusesAnEmptyKey) {
  EXPECT_THROW(embed_watermark(low_poly_model(), "", bits_from_hex("ab")), std::invalid_argument);
  EXPECT_THROW(detect_watermark(low_poly_model(), low_poly_model().mesh, ""), std::invalid_argument);
}

TEST(Watermark, RefusesAStrengthOutsideTheBudgetRange) {
  WatermarkOptions options;
  options.strength_percent = 0;
  EXPECT_THROW(embed_watermark(low_poly_model(), "k", bits_from_hex("ab"), options), std::invalid_argument);
}

TEST(Watermark, ExpectedPayloadOfTheWrongLengthIsRefused) {
  DetectOptions d;
  d.expected = bits_from_hex("ab");  // 8 bits, but 64 asked for
  try {
    detect_watermark(low_poly_model(), low_poly_model().mesh, "k", d);
    FAIL() << "an 8-bit expected payload was taken for 64 bits";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("has 8 bits"), std::string::npos) << e.what();
  }
}

TEST(Watermark, ShorterPayloadsRoundTrip) {
  const Bits payload = bits_from_hex("5a5a");
  const EmbedResult e = embed_watermark(low_poly_model(), "short", payload);
  DetectOptions d;
  d.payload_bits = 16;
  d.expected = payload;
  const DetectResult r = detect_watermark(low_poly_model(), e.mesh, "short", d);
  EXPECT_EQ(r.ber, 0.0);
  EXPECT_TRUE(r.detected);
}

// A 16-bit mark on a low-poly model, read through registration after a re-save, 12-bit
// quantization and a similarity: BER 0 and a decision; another key decides nothing.
void expect_sixteen_bits_survive_a_resave(const PreparedModel& model) {
  const Bits payload = bits_from_hex("c0de");
  const EmbedResult e = embed_watermark(model, "low poly", payload);
  const Mesh suspect =
      apply_attack_chain(e.mesh, parse_attack_chain("quantize bits=12 | similarity | digits digits=6"), 7);
  DetectOptions d;
  d.payload_bits = 16;
  d.expected = payload;
  const DetectResult r = detect_watermark(model, suspect, "low poly", d);
  EXPECT_EQ(r.ber, 0.0);
  EXPECT_TRUE(r.detected);
  EXPECT_FALSE(detect_watermark(model, suspect, "another key", d).detected);
}

// 162 vertices: no band holds a carrier per coded bit, so the code is punctured on one band.
TEST(Watermark, ALowPolyMeshCarriesSixteenBits) {
  const PreparedModel model = prepare_model(test::creature(2));
  ASSERT_EQ(model.mesh.V.rows(), 162);
  expect_sixteen_bits_survive_a_resave(model);
}

// Eight parts of 42 vertices (sized apart, so no shift maps the row onto itself), each below
// kMinMarkedComponentVertices: together they carry one payload, as a low-poly model's parts should.
TEST(Watermark, ManySmallPartsShareOnePayload) {
  Mesh parts = test::creature(1);
  for (int k = 1; k < 8; ++k) {
    Mesh part = test::creature(1);
    part.V *= 1.0 + 0.2 * k;
    parts = test::side_by_side(parts, part, 3.0 * k);
  }
  const PreparedModel model = prepare_model(parts);
  EXPECT_EQ(model.report.marked_component_floor, kMinLowPolyComponentVertices);
  EXPECT_EQ(model.report.small_components, 0u);
  ASSERT_EQ(model.basis, MeshBasis::bumps);
  EXPECT_EQ(model.bumps->marked_components, 8u);
  expect_sixteen_bits_survive_a_resave(model);
}

TEST(FalseAlarmBound, IsTheUnionBoundOverTheCandidates) {
  EXPECT_DOUBLE_EQ(false_alarm_bound(0.0, 10), 1.0);
  EXPECT_DOUBLE_EQ(false_alarm_bound(-3.0, 0), 1.0);
  EXPECT_NEAR(false_alarm_bound(10.0, 0), std::exp(-50.0), 1e-30);
  EXPECT_NEAR(false_alarm_bound(12.0, 16), 65536 * std::exp(-72.0), 1e-30);
  EXPECT_DOUBLE_EQ(false_alarm_bound(3.0, 64), 1.0);
}

}  // namespace
}  // namespace meshmark
