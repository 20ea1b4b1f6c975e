#pragma once
// Where and how strongly the spread scheme writes each coded bit. Derived only from the
// original (prepared model), the key and the payload length, so embedder and detector build the
// same plan.
//
// Carriers are the basis coefficients (spherical wavelets or bumps, see carrier_field.hpp) of a
// scalar normal-displacement field in the bands whose functions cover at least
// `min_support_vertices` vertices and that hold at least one carrier per coded bit. Within each band the carriers are
// shuffled by the keyed generator and dealt to the coded bits in turn, so every bit gets the same share of every band;
// each carrier gets a keyed ±1 chip. Every band carries the same energy, and within a band a carrier's amplitude
// follows the roughness of the original around it (the paper's masking idea), within ×0.5..×2.

#include <algorithm>
#include <string>
#include <vector>

#include "core/watermark/carrier_field.hpp"
#include "core/watermark/prepared_model.hpp"
#include "core/watermark/watermark_options.hpp"

namespace meshmark {

struct SpreadPlan {
  std::vector<int> levels;       ///< labels of the carrying bands (grid levels, or bump bands)
  std::vector<int> coefficient;  ///< per carrier: its index in the coefficient signal
  std::vector<int> bit;          ///< per carrier: the coded bit it carries
  std::vector<int> band;         ///< per carrier: index into `levels`
  Eigen::VectorXd weight;        ///< per carrier: chip × relative amplitude
  int coded_bits = 0;
};

/// Throws std::invalid_argument when no band qualifies (the mesh is too small for the payload).
SpreadPlan make_spread_plan(const PreparedModel& model, const CarrierField& field, const std::string& key,
                            int payload_bits, const WatermarkOptions& options);

/// Carriers per coded bit, in one band of the full width, that a payload needs to survive
/// halving and remeshing (measured on the 1,148-vertex beetle: 1.02 per bit read 5 keys of 6
/// after halving, 1.32 all 12).
inline constexpr double kRobustCarriersPerCodedBit = 1.25;

/// A small mesh may carry a payload of up to kMaxPuncturedPayloadBits on one band with fewer
/// carriers than coded bits, down to kMinPuncturedCoverage of them: the bits left without a
/// carrier are erasures the rate-1/3 code fills in (a punctured code), and every copy is read
/// back before it is handed out. Longer payloads keep the strict rule.
inline constexpr int kMaxPuncturedPayloadBits = 16;
inline constexpr double kMinPuncturedCoverage = 0.5;
/// ... on functions that cover at least this many vertices: such a mesh is too small to be
/// simplified or remeshed and keep its look, so narrow functions are worth their capacity.
inline constexpr double kMinPuncturedSupport = 1;

/// The longest payload (a multiple of 4 bits, at most 1024) that one band of the full width
/// carries with kRobustCarriersPerCodedBit; 0 if none.
int robust_payload_bits(const CarrierField& field, const WatermarkOptions& options);

/// The payloads assigned to copies, one per recipient (the daemon's, embed --recipients): what the
/// model keeps through simplification and remeshing, in whole bytes within these bounds; a model
/// that cannot carry the shortest is refused.
inline constexpr int kMinAssignedPayloadBits = 16;
inline constexpr int kMaxAssignedPayloadBits = 64;
inline int assigned_payload_bits(int robust_bits) {
  return std::clamp(robust_bits / 8 * 8, kMinAssignedPayloadBits, kMaxAssignedPayloadBits);
}

/// The longest payload (a multiple of 4 bits, at most 1024) make_spread_plan accepts with
/// `options`; 0 if none: what a refusal names.
int payload_capacity_bits(const CarrierField& field, const WatermarkOptions& options);

/// The coefficients that write `codeword` (±1 per coded bit): Σ weight_k · s_bit(k) at coefficient_k.
Eigen::VectorXd plan_coefficients(const SpreadPlan& plan, const std::vector<double>& signs, int rows);

/// The label the key is combined with: scheme and model, so one key marks different models
/// with unrelated chips.
std::string chip_label(const std::string& scheme, const PreparedModel& model);

}  // namespace meshmark
