#include "core/watermark/spread_scheme.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>

#include "core/watermark/nuisance_fields.hpp"
#include "core/watermark/spread_plan.hpp"
#include "core/watermark/vertex_field.hpp"

namespace meshmark {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::vector<double> signs_of(const Bits& bits) {
  std::vector<double> s(bits.size());
  for (std::size_t i = 0; i < bits.size(); ++i) s[i] = bits[i] ? 1.0 : -1.0;
  return s;
}

// Soft value of each coded bit: Σ over its carriers of band weight × contribution.
std::vector<double> soft_bits(const SpreadPlan& plan, const Eigen::VectorXd& contribution,
                              const std::vector<double>& band_weight) {
  std::vector<double> soft(static_cast<std::size_t>(plan.coded_bits), 0.0);
  for (std::size_t k = 0; k < plan.bit.size(); ++k) soft[plan.bit[k]] += band_weight[plan.band[k]] * contribution[k];
  return soft;
}

// Robust clipping of the measured displacements at 6 median absolute deviations: a few
// readings off the surface (the far side of a thin part) must not outweigh thousands.
void clip_outliers(Eigen::VectorXd& t, const std::vector<char>& found) {
  std::vector<double> a;
  for (Eigen::Index i = 0; i < t.size(); ++i)
    if (found[i]) a.push_back(std::abs(t[i]));
  if (a.empty()) return;
  std::nth_element(a.begin(), a.begin() + static_cast<long>(a.size() / 2), a.end());
  const double limit = 6 * a[a.size() / 2] / 0.6745;
  if (limit > 0) t = t.cwiseMax(-limit).cwiseMin(limit);
}

}  // namespace

EmbedResult embed_spread(const PreparedModel& model, const std::string& key, const Bits& payload,
                         const WatermarkOptions& options) {
  EmbedResult result;
  auto t0 = Clock::now();
  const SphericalWavelet wavelet(*model.grid, model.level(), options.wavelet);
  const SpreadPlan plan = make_spread_plan(model, wavelet, key, static_cast<int>(payload.size()), options);
  result.seconds["plan"] = since(t0);

  t0 = Clock::now();
  const Bits codeword = encode_payload(payload);
  const Eigen::VectorXd c = plan_coefficients(plan, signs_of(codeword), model.sample_count());
  const Eigen::VectorXd u = coefficients_to_vertices(model, wavelet, c);
  result.seconds["synthesis"] = since(t0);

  t0 = Clock::now();
  const double rms = std::sqrt(u.cwiseProduct(u).dot(model.vertex_area) / model.vertex_area.sum());
  const double alpha = options.strength_percent / 100.0 * model.diagonal / rms;
  result.mesh = model.mesh;
  for (Eigen::Index i = 0; i < u.size(); ++i) result.mesh.V.row(i) += alpha * u[i] * model.normals.row(i);
  result.seconds["apply"] = since(t0);

  result.carriers = static_cast<int>(plan.coefficient.size());
  result.carrier_levels = plan.levels;
  result.coded_bits = plan.coded_bits;
  result.rms_displacement = alpha * rms / model.diagonal;
  result.max_displacement = alpha * u.cwiseAbs().maxCoeff() / model.diagonal;
  return result;
}

namespace {

// The Gram matrix of the carriers' vertex patterns, G = D_cᵀ D_c, applied without forming it.
class CarrierGram {
 public:
  CarrierGram(const PreparedModel& model, const SphericalWavelet& wavelet, const SpreadPlan& plan)
      : model_(model), wavelet_(wavelet), plan_(plan) {}

  Eigen::VectorXd operator()(const Eigen::VectorXd& v) const {
    Eigen::VectorXd c = Eigen::VectorXd::Zero(model_.sample_count());
    for (std::size_t k = 0; k < plan_.coefficient.size(); ++k) c[plan_.coefficient[k]] = v[k];
    return carriers(vertices_to_coefficients(model_, wavelet_, coefficients_to_vertices(model_, wavelet_, c)));
  }
  Eigen::VectorXd carriers(const Eigen::VectorXd& grid_values) const {
    Eigen::VectorXd out(static_cast<Eigen::Index>(plan_.coefficient.size()));
    for (std::size_t k = 0; k < plan_.coefficient.size(); ++k) out[k] = grid_values[plan_.coefficient[k]];
    return out;
  }
  // Mean of the diagonal, by one Hutchinson probe with a fixed sign pattern.
  double mean_diagonal() const {
    Eigen::VectorXd r(static_cast<Eigen::Index>(plan_.coefficient.size()));
    for (Eigen::Index k = 0; k < r.size(); ++k) r[k] = (k * 2654435761u >> 7) & 1 ? 1.0 : -1.0;
    return r.dot((*this)(r)) / static_cast<double>(r.size());
  }

 private:
  const PreparedModel& model_;
  const SphericalWavelet& wavelet_;
  const SpreadPlan& plan_;
};

// (G + μI) c = x by conjugate gradients, to a loose tolerance: the estimate only feeds correlations.
Eigen::VectorXd regularized_solve(const CarrierGram& G, const Eigen::VectorXd& x, double mu, double diagonal) {
  Eigen::VectorXd c = x / (diagonal + mu), r = x - (G(c) + mu * c), p = r;
  double rr = r.squaredNorm();
  const double stop = 1e-6 * x.squaredNorm();
  for (int it = 0; it < 60 && rr > stop; ++it) {
    const Eigen::VectorXd Ap = G(p) + mu * p;
    const double a = rr / p.dot(Ap);
    c += a * p;
    r -= a * Ap;
    const double next = r.squaredNorm();
    p = r + (next / rr) * p;
    rr = next;
  }
  return c;
}

struct Reading {
  DecodedPayload decoded;
  double z = 0;
  std::vector<double> pass1;  // the chip-independent band weights behind z
  Eigen::VectorXd q;
};

// Decodes carrier contributions q (two passes) and scores the result.
Reading read_carriers(const SpreadPlan& plan, const Eigen::VectorXd& q, int payload_bits) {
  Reading r;
  r.q = q;
  const std::size_t bands = plan.levels.size();
  std::vector<double> power(bands, 0.0), count(bands, 0.0);
  for (std::size_t k = 0; k < plan.band.size(); ++k) power[plan.band[k]] += q[k] * q[k], count[plan.band[k]] += 1;
  // Pass 1: each band scaled by its own spread. These weights ignore the chips, so the statistic
  // below is a sum of fixed weights with random signs when there is no watermark.
  r.pass1.resize(bands);
  for (std::size_t b = 0; b < bands; ++b) r.pass1[b] = power[b] > 0 ? 1.0 / std::sqrt(power[b] / count[b]) : 0.0;
  r.decoded = decode_payload(soft_bits(plan, q, r.pass1), payload_bits);

  // Pass 2: weight each band by its signal-to-noise ratio read along the first decode.
  std::vector<double> mean(bands, 0.0), var(bands, 0.0), w2(bands, 0.0);
  const std::vector<double> first = signs_of(r.decoded.codeword);
  for (std::size_t k = 0; k < plan.band.size(); ++k) mean[plan.band[k]] += q[k] * first[plan.bit[k]] / count[plan.band[k]];
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

// How many carrier estimates detection tries: each costs a factor in the false-alarm bound.
constexpr double kRegularizations[] = {0.0 /* the plain matched filter */, 1.0};

}  // namespace

void detect_spread(const PreparedModel& model, const Mesh& aligned, const std::string& key,
                   const DetectOptions& options, DetectResult& result) {
  auto t0 = Clock::now();
  const AabbTree tree(aligned.V, aligned.F);
  Displacement d = measure_displacement(tree, model.mesh.V, model.normals, model.diagonal, options.displacement);
  clip_outliers(d.t, d.found);
  remove_fit(d.t, d.found, nuisance_fields(model.mesh, model.normals));
  result.samples = static_cast<std::size_t>(d.t.size());
  result.missing = d.missing;
  result.seconds["resample"] = since(t0);

  t0 = Clock::now();
  const SphericalWavelet wavelet(*model.grid, model.level(), options.watermark.wavelet);
  const SpreadPlan plan = make_spread_plan(model, wavelet, key, options.payload_bits, options.watermark);
  const CarrierGram gram(model, wavelet, plan);
  const Eigen::VectorXd x = gram.carriers(vertices_to_coefficients(model, wavelet, d.t));  // the matched filter
  const double diagonal = gram.mean_diagonal();
  Reading best;
  best.z = -std::numeric_limits<double>::infinity();
  for (double relative : kRegularizations) {
    // Regularized least squares over the carriers: μ → ∞ is the matched filter (best in heavy
    // noise), small μ undoes the overlap of neighbouring carriers (best in light noise).
    const Eigen::VectorXd c = relative == 0 ? x : regularized_solve(gram, x, relative * diagonal, diagonal);
    Reading r = read_carriers(plan, plan.weight.cwiseProduct(c), options.payload_bits);
    // A reading whose checksum matches beats one whose does not; then the larger statistic wins
    // (statistics from different estimators are not comparable enough to overrule a checksum).
    const bool better = r.decoded.checksum_ok != best.decoded.checksum_ok ? r.decoded.checksum_ok : r.z > best.z;
    if (better) best = std::move(r);
  }
  result.seconds["filter"] = since(t0);

  t0 = Clock::now();
  result.decoded = best.decoded.payload;
  result.checksum_ok = best.decoded.checksum_ok;
  if (best.decoded.checksum_ok) result.payload = best.decoded.payload;
  result.z_score = best.z;
  const int tries = static_cast<int>(std::ceil(std::log2(std::size(kRegularizations))));
  result.p_value = false_alarm_bound(result.z_score, options.payload_bits + kCrcBits + tries);
  if (options.expected) {
    const std::vector<double> expected = signs_of(encode_payload(*options.expected));
    double e = 0, den = 0;
    for (std::size_t k = 0; k < plan.band.size(); ++k) {
      const double v = best.pass1[plan.band[k]] * best.q[k];
      e += v * expected[plan.bit[k]];
      den += v * v;
    }
    result.expected_p_value = false_alarm_bound(den > 0 ? e / std::sqrt(den) : 0.0, tries);
  }
  // Correlation of the measured field with the decoded watermark's field, where measured.
  const Eigen::VectorXd pattern = coefficients_to_vertices(
      model, wavelet, plan_coefficients(plan, signs_of(best.decoded.codeword), model.sample_count()));
  double pm = 0, pp = 0, mm = 0;
  for (Eigen::Index i = 0; i < pattern.size(); ++i)
    if (d.found[i]) pm += pattern[i] * d.t[i], pp += pattern[i] * pattern[i], mm += d.t[i] * d.t[i];
  result.correlation = pp > 0 && mm > 0 ? pm / std::sqrt(pp * mm) : 0.0;
  result.seconds["decode"] = since(t0);
}

}  // namespace meshmark
