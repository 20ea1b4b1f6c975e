#include "core/watermark/spread_plan.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/util/keyed_random.hpp"
#include "core/watermark/payload_code.hpp"

namespace meshmark {

std::string chip_label(const std::string& scheme, const PreparedModel& model) {
  return "meshmark/1/" + scheme + "/" + model.digest;
}

namespace {

// Bands whose functions are wide enough on the mesh and numerous enough for the code (indices
// into field.bands()). A grid whose levels straddle the threshold (octahedron on a small mesh)
// falls back to half the width.
std::vector<int> bands_of_width(const CarrierField& field, double carriers_needed, double min_support) {
  std::vector<int> chosen;
  for (std::size_t b = 0; b < field.bands().size(); ++b) {
    const CarrierBand& band = field.bands()[b];
    if (band.support >= min_support && static_cast<double>(band.members.size()) >= carriers_needed)
      chosen.push_back(static_cast<int>(b));
  }
  return chosen;
}

// The strict rule first; a small mesh falls back to half the width, then, for a short payload, to
// a punctured band (the widest that qualifies; some coded bits without a carrier: erasures the
// code's redundancy fills in).
std::vector<int> carrier_bands(const CarrierField& field, int coded, const WatermarkOptions& options) {
  const double full = options.min_carriers_per_bit * coded;
  std::vector<int> chosen = bands_of_width(field, full, options.min_support_vertices);
  if (chosen.empty()) chosen = bands_of_width(field, full, options.min_support_vertices / 2);
  if (chosen.empty() && coded <= coded_length(kMaxPuncturedPayloadBits)) {
    chosen = bands_of_width(field, kMinPuncturedCoverage * coded, kMinPuncturedSupport);
    if (!chosen.empty()) chosen = {chosen.front()};  // the widest functions that qualify
  }
  if (options.max_bands > 0 && static_cast<int>(chosen.size()) > options.max_bands)
    chosen.erase(chosen.begin(), chosen.end() - options.max_bands);
  return chosen;
}

// The coded bit of a band's i-th carrier (of n): in turn from a keyed offset; a punctured band
// (fewer carriers than coded bits) spaces its carriers evenly over the code, so the erased bits
// are spread out rather than one burst the decoder cannot bridge.
int dealt_bit(std::size_t i, std::size_t n, int offset, int coded) {
  const auto c = static_cast<std::size_t>(coded);
  const std::size_t step = n >= c ? i : i * c / n;
  return static_cast<int>((step + static_cast<std::size_t>(offset)) % c);
}

}  // namespace

int robust_payload_bits(const CarrierField& field, const WatermarkOptions& options) {
  WatermarkOptions margin = options;
  margin.min_carriers_per_bit = std::max(options.min_carriers_per_bit, kRobustCarriersPerCodedBit);
  int widest = 0;
  for (int bits = 4; bits <= 1024; bits += 4)
    if (!bands_of_width(field, margin.min_carriers_per_bit * coded_length(bits), options.min_support_vertices).empty())
      widest = bits;
  return widest;
}

int payload_capacity_bits(const CarrierField& field, const WatermarkOptions& options) {
  int widest = 0;
  for (int bits = 4; bits <= 1024 && !carrier_bands(field, coded_length(bits), options).empty(); bits += 4)
    widest = bits;
  return widest;
}

Eigen::VectorXd plan_coefficients(const SpreadPlan& plan, const std::vector<double>& signs, int rows) {
  Eigen::VectorXd c = Eigen::VectorXd::Zero(rows);
  for (std::size_t k = 0; k < plan.coefficient.size(); ++k)
    c[plan.coefficient[k]] += plan.weight[k] * signs[plan.bit[k]];
  return c;
}

SpreadPlan make_spread_plan(const PreparedModel& model, const CarrierField& field, const std::string& key,
                            int payload_bits, const WatermarkOptions& options) {
  SpreadPlan plan;
  plan.coded_bits = coded_length(payload_bits);
  const std::vector<int> bands = carrier_bands(field, plan.coded_bits, options);
  if (bands.empty()) {
    const int capacity = payload_capacity_bits(field, options);
    throw std::invalid_argument("the mesh has too few vertices (" + std::to_string(model.mesh.V.rows()) +
                                ") to carry a " + std::to_string(payload_bits) + "-bit payload; " +
                                (capacity > 0 ? "it carries at most " + std::to_string(capacity) + " bits (" +
                                                    std::to_string(capacity / 4) + " hex digits)"
                                              : "it cannot carry a payload with these settings"));
  }
  const Eigen::VectorXd rough = field.relative_roughness(bands);
  const std::string label = chip_label("spread", model);
  for (std::size_t b = 0; b < bands.size(); ++b) {
    const CarrierBand& band = field.bands()[static_cast<std::size_t>(bands[b])];
    plan.levels.push_back(band.label);
    std::vector<int> carriers = band.members;
    KeyedRandom random(key, label + "/band/" + std::to_string(band.label));
    random.shuffle(carriers);
    const auto offset = static_cast<int>(random.below(static_cast<std::uint64_t>(plan.coded_bits)));
    const std::size_t first = plan.coefficient.size();
    for (std::size_t i = 0; i < carriers.size(); ++i) {
      plan.coefficient.push_back(carriers[i]);
      plan.bit.push_back(dealt_bit(i, carriers.size(), offset, plan.coded_bits));
      plan.band.push_back(static_cast<int>(b));
    }
    plan.weight.conservativeResize(static_cast<Eigen::Index>(plan.coefficient.size()));
    for (std::size_t i = first; i < plan.coefficient.size(); ++i)
      plan.weight[i] = random.sign() * rough[plan.coefficient[i]];
  }
  // Equal energy per band: measure each band's field at the vertices (area-weighted).
  const std::vector<double> ones(static_cast<std::size_t>(plan.coded_bits), 1.0);
  for (std::size_t b = 0; b < plan.levels.size(); ++b) {
    SpreadPlan band_only = plan;
    for (std::size_t i = 0; i < plan.band.size(); ++i)
      if (plan.band[i] != static_cast<int>(b)) band_only.weight[i] = 0;
    const Eigen::VectorXd u = field.to_vertices(plan_coefficients(band_only, ones, static_cast<int>(field.size())));
    const double energy = u.cwiseProduct(u).dot(model.vertex_area) / model.vertex_area.sum();
    for (std::size_t i = 0; i < plan.band.size(); ++i)
      if (plan.band[i] == static_cast<int>(b)) plan.weight[i] /= std::sqrt(energy);
  }
  return plan;
}

}  // namespace meshmark
