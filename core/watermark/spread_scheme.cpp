#include "core/watermark/spread_scheme.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>
#include <optional>

#include "core/metrics/surface_rms.hpp"
#include "core/util/stopwatch.hpp"
#include "core/watermark/carrier_cache.hpp"
#include "core/watermark/carrier_estimate.hpp"
#include "core/watermark/spread_plan.hpp"
#include "core/watermark/carrier_field.hpp"
#include "core/watermark/detect_stages.hpp"
#include "core/watermark/embed_steps.hpp"
#include "core/watermark/known_payload_scores.hpp"
#include "core/watermark/watermark.hpp"

namespace meshmark {

namespace {

using Clock = std::chrono::steady_clock;

// Soft value of each coded bit: Σ over its carriers of band weight × contribution.
std::vector<double> soft_bits(const SpreadPlan& plan, const Eigen::VectorXd& contribution,
                              const std::vector<double>& band_weight) {
  std::vector<double> soft(static_cast<std::size_t>(plan.coded_bits), 0.0);
  for (std::size_t k = 0; k < plan.bit.size(); ++k) soft[plan.bit[k]] += band_weight[plan.band[k]] * contribution[k];
  return soft;
}

// The spread scheme's embedding: the coded payload's signs on the planned carriers, as one
// normal displacement field scaled to the RMS budget.
class SpreadEmbedding final : public EmbedSteps {
 public:
  explicit SpreadEmbedding(const EmbedInputs& request) : request_(request) {}

  void plan() override {
    CarrierCache& cache = carrier_cache(request_.model);
    field_ = &cache.field(request_.model, request_.options.wavelet, request_.threads);
    plan_ = cache.plan(request_.model, request_.key, static_cast<int>(request_.payload.size()), request_.options,
                       request_.threads);
  }

  void synthesize() override {
    pattern_ = carrier_cache(request_.model).pattern(plan_, *field_, encode_payload(request_.payload));
  }

  void apply(EmbedResult& result) override {
    // The budget is the RMS over the surface of the (piecewise-linear) displacement.
    const Eigen::VectorXd& u = *pattern_;
    rms_ = surface_rms(request_.model.mesh, u);
    alpha_ = request_.options.strength_percent / 100.0 * request_.model.diagonal / rms_;
    result.mesh = request_.model.mesh;
    for (Eigen::Index i = 0; i < u.size(); ++i) result.mesh.V.row(i) += alpha_ * u[i] * request_.model.normals.row(i);
  }

  void describe(EmbedResult& result) const override {
    result.carriers = static_cast<int>(plan_->coefficient.size());
    result.carrier_levels = plan_->levels;
    result.coded_bits = plan_->coded_bits;
    result.rms_displacement = alpha_ * rms_ / request_.model.diagonal;
    result.max_displacement = alpha_ * pattern_->cwiseAbs().maxCoeff() / request_.model.diagonal;
    if (const int robust = robust_payload_bits(*field_, request_.options);
        static_cast<int>(request_.payload.size()) > robust)
      result.warnings.push_back(
          robust > 0 ? "the payload is long for this mesh: its wide carriers hold " + std::to_string(robust) +
                           " bits with a margin, and simplifying or remeshing a copy with " +
                           std::to_string(request_.payload.size()) + " may erase it; use " + std::to_string(robust) +
                           " bits or fewer"
                     : std::string("the mesh is small for any payload: none of its carrier bands is wide and numerous "
                                   "enough to keep a code through simplification or remeshing"));
  }

 private:
  const EmbedInputs request_;
  const CarrierField* field_ = nullptr;
  std::shared_ptr<const SpreadPlan> plan_;
  std::shared_ptr<const Eigen::VectorXd> pattern_;  // the unscaled displacement along the normal at each vertex
  double rms_ = 0, alpha_ = 0;
};

}  // namespace

EmbedResult embed_spread(const PreparedModel& model, const std::string& key, const Bits& payload,
                         const WatermarkOptions& options, const JobControl* control) {
  SpreadEmbedding steps({model, key, payload, options, threads_of(control)});
  return run_embed_steps(steps, control);
}

namespace {

struct Reading {
  DecodedPayload decoded;
  double z = 0;
  std::vector<double> pass1;  // the chip-independent band weights behind z
  Eigen::VectorXd q;
};

// First-pass band weights: either each band scaled by its own spread (a band an attack has
// destroyed then cannot swamp the others), or none at all (q already carries each carrier's
// designed amplitude: the matched filter when the noise is white). Neither looks at the chips, so
// the statistic below is a sum of fixed weights with random signs when there is no watermark.
std::vector<double> first_pass_weights(const SpreadPlan& plan, const Eigen::VectorXd& q, bool per_band) {
  const std::size_t bands = plan.levels.size();
  std::vector<double> w(bands, 1.0);
  if (!per_band) return w;
  std::vector<double> power(bands, 0.0), count(bands, 0.0);
  for (std::size_t k = 0; k < plan.band.size(); ++k) power[plan.band[k]] += q[k] * q[k], count[plan.band[k]] += 1;
  for (std::size_t b = 0; b < bands; ++b) w[b] = power[b] > 0 ? 1.0 / std::sqrt(power[b] / count[b]) : 0.0;
  return w;
}

// Decodes carrier contributions q (two passes) and scores the result.
Reading read_carriers(const SpreadPlan& plan, const Eigen::VectorXd& q, int payload_bits, bool per_band) {
  Reading r;
  r.q = q;
  const std::size_t bands = plan.levels.size();
  r.pass1 = first_pass_weights(plan, q, per_band);
  r.decoded = decode_payload(soft_bits(plan, q, r.pass1), payload_bits);

  // Pass 2: weight each band by its signal-to-noise ratio read along the first decode.
  std::vector<double> count(bands, 0.0), mean(bands, 0.0), var(bands, 0.0), w2(bands, 0.0);
  for (std::size_t k = 0; k < plan.band.size(); ++k) count[plan.band[k]] += 1;
  const std::vector<double> first = signs_of(r.decoded.codeword);
  for (std::size_t k = 0; k < plan.band.size(); ++k)
    mean[plan.band[k]] += q[k] * first[plan.bit[k]] / count[plan.band[k]];
  for (std::size_t k = 0; k < plan.band.size(); ++k) {
    const double e = q[k] * first[plan.bit[k]] - mean[plan.band[k]];
    var[plan.band[k]] += e * e / count[plan.band[k]];
  }
  bool any = false;
  for (std::size_t b = 0; b < bands; ++b) {
    w2[b] = var[b] > 0 ? std::max(mean[b], 0.0) / var[b] : 0.0;
    any = any || w2[b] > 0;
  }
  if (any) r.decoded = decode_payload(soft_bits(plan, q, w2), payload_bits);

  const std::vector<double> chosen = signs_of(r.decoded.codeword);
  double num = 0, den = 0;
  for (std::size_t k = 0; k < plan.band.size(); ++k) {
    const double v = r.pass1[plan.band[k]] * q[k];
    num += v * chosen[plan.bit[k]];
    den += v * v;
  }
  r.z = den > 0 ? num / std::sqrt(den) : 0.0;
  return r;
}

// Step 1, estimate: each carrier's contribution q (its designed weight × its estimated amplitude),
// once per regularization, all from one multi-shift solve.
std::vector<Eigen::VectorXd> estimate_contributions(const CarrierField& field, const SpreadPlan& plan,
                                                    const Displacement& d, const std::vector<double>& regularizations) {
  // A: carrier amplitudes → normal displacement at the vertices (the displacement is along n).
  auto to_grid = [&](const Eigen::VectorXd& s) {
    Eigen::VectorXd c = Eigen::VectorXd::Zero(field.size());
    for (std::size_t k = 0; k < plan.coefficient.size(); ++k) c[plan.coefficient[k]] = s[k];
    return c;
  };
  auto from_grid = [&](const Eigen::VectorXd& c) {
    Eigen::VectorXd s(static_cast<Eigen::Index>(plan.coefficient.size()));
    for (std::size_t k = 0; k < plan.coefficient.size(); ++k) s[k] = c[plan.coefficient[k]];
    return s;
  };
  const CarrierEstimator estimator(
      [&](const Eigen::VectorXd& s) -> Eigen::VectorXd { return field.to_vertices(to_grid(s)); },
      [&](const Eigen::VectorXd& t) -> Eigen::VectorXd { return from_grid(field.from_vertices(t)); },
      static_cast<Eigen::Index>(plan.coefficient.size()));
  std::vector<Eigen::VectorXd> estimates = estimator.estimates(estimator.matched(d.t), regularizations);
  for (Eigen::VectorXd& e : estimates) e = plan.weight.cwiseProduct(e);
  return estimates;
}

// Step 2, choose: every estimate decoded under both first-pass weightings; a reading whose
// checksum matches beats one whose does not, then the larger statistic wins (statistics from
// different estimators are not comparable enough to overrule a checksum).
Reading choose_reading(const SpreadPlan& plan, const std::vector<Eigen::VectorXd>& estimates, int payload_bits) {
  Reading best;
  best.z = -std::numeric_limits<double>::infinity();
  for (const Eigen::VectorXd& q : estimates) {
    for (bool per_band : {true, false}) {
      Reading r = read_carriers(plan, q, payload_bits, per_band);
      const bool better = r.decoded.checksum_ok != best.decoded.checksum_ok ? r.decoded.checksum_ok : r.z > best.z;
      if (better) best = std::move(r);
    }
  }
  return best;
}

// Normalized correlation of the measured field with the decoded watermark's, where measured.
double field_correlation(const Eigen::VectorXd& pattern, const Displacement& d) {
  double pm = 0, pp = 0, mm = 0;
  for (Eigen::Index i = 0; i < pattern.size(); ++i)
    if (d.found[i]) pm += pattern[i] * d.t[i], pp += pattern[i] * pattern[i], mm += d.t[i] * d.t[i];
  return pp > 0 && mm > 0 ? pm / std::sqrt(pp * mm) : 0.0;
}

// Step 3, score: the blind decode's p-value, the known payloads', the correlation.
DetectResult score_reading(const Reading& best, CarrierCache& cache, const CarrierField& field,
                           const std::shared_ptr<const SpreadPlan>& plan_held, const Displacement& d,
                           const DetectOptions& options) {
  const SpreadPlan& plan = *plan_held;
  DetectResult result;
  result.decoded = best.decoded.payload;
  result.checksum_ok = best.decoded.checksum_ok;
  if (best.decoded.checksum_ok) result.payload = best.decoded.payload;
  result.z_score = best.z;
  const int tries =
      bits_for_tries(2 * options.estimate.charged(options.estimate.spread_regularizations.size()));  // × weightings
  // A decode whose checksum matches is one of 2^bits valid words; one that fails, of 2^(bits+16).
  // One more bit pays for reading the checksum before choosing the bound (combine_evidence.hpp).
  const int words = options.payload_bits + (best.decoded.checksum_ok ? 0 : kCrcBits) + 1;
  result.blind_log10_p_value = log10_false_alarm_bound(result.z_score, words + tries);
  Eigen::VectorXd votes(static_cast<Eigen::Index>(plan.band.size()));
  double norm2 = 0;
  for (std::size_t k = 0; k < plan.band.size(); ++k) {
    votes[static_cast<Eigen::Index>(k)] = best.pass1[plan.band[k]] * best.q[k];
    norm2 += votes[static_cast<Eigen::Index>(k)] * votes[static_cast<Eigen::Index>(k)];
  }
  score_known_payloads(options, tries, [&](const Bits& payload) {
    return vote_statistic(votes, plan.bit, signs_of(encode_payload(payload)), norm2);
  }).write_to(result);
  result.correlation = field_correlation(*cache.pattern(plan_held, field, best.decoded.codeword), d);
  return result;
}

}  // namespace

DetectResult detect_spread(const PreparedModel& model, const Displacement& d, const std::string& key,
                           const DetectOptions& options, const JobControl* control) {
  auto t0 = Clock::now();
  CarrierCache& cache = carrier_cache(model);
  const CarrierField& field = cache.field(model, options.watermark.wavelet, threads_of(control));
  const std::shared_ptr<const SpreadPlan> plan =
      cache.plan(model, key, options.payload_bits, options.watermark, threads_of(control));
  const std::vector<Eigen::VectorXd> estimates =
      estimate_contributions(field, *plan, d, options.estimate.spread_regularizations);
  const double estimate_seconds = seconds_since(t0);
  checkpoint(control, detect_stage::decode, 0.8);
  t0 = Clock::now();
  const Reading best = choose_reading(*plan, estimates, options.payload_bits);
  DetectResult result = score_reading(best, cache, field, plan, d, options);
  result.seconds[detect_stage::estimate] = estimate_seconds;
  result.seconds[detect_stage::decode] = seconds_since(t0);
  return result;
}

}  // namespace meshmark
