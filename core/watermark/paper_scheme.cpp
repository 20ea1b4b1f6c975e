#include "core/watermark/paper_scheme.hpp"

#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>

#include "core/watermark/carrier_estimate.hpp"
#include "core/watermark/keyed_random.hpp"
#include "core/watermark/spread_plan.hpp"
#include "core/grid/sample_on_grid.hpp"

namespace meshmark {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The carrier estimates detection tries (relative regularization; 0 = the plain matched filter).
constexpr double kRegularizations[] = {0.0, 1.0, 0.01};

// The coarsest level of the decomposition: the approximation band is [0, V_coarsest).
constexpr int kCoarsest = 3;

struct PaperPlan {
  int coarsest = kCoarsest;
  int finest_carrier_level = 0;
  std::vector<int> coefficient;     // carrier → grid index
  std::vector<int> bit;             // carrier → payload bit
  std::vector<double> chip;         // carrier → ±1
  std::vector<double> strength;     // carrier → f(c)
  std::vector<Eigen::Vector3d> direction;  // carrier → ĉ
};

// The sampled geometry, centred and scaled to a unit bounding-box diagonal, transformed.
Eigen::MatrixXd geometry_coefficients(const PreparedModel& model, const SphericalWavelet& wavelet, int coarsest) {
  Eigen::MatrixXd c = model.sampling.positions;
  const Eigen::RowVector3d centre = 0.5 * (model.mesh.V.colwise().maxCoeff() + model.mesh.V.colwise().minCoeff());
  c = (c.rowwise() - centre) / model.diagonal;
  wavelet.forward(c, coarsest);
  return c;
}

PaperPlan make_paper_plan(const PreparedModel& model, const SphericalWavelet& wavelet, const std::string& key,
                          int payload_bits, const WatermarkOptions& options) {
  PaperPlan plan;
  plan.coarsest = std::min(kCoarsest, model.level() - 1);
  // Detail bands as fine as the spread scheme allows (bumps wide enough to survive resampling).
  plan.finest_carrier_level = plan.coarsest;
  for (int level = plan.coarsest + 1; level <= model.level(); ++level)
    if (3.0 * static_cast<double>(model.mesh.V.rows()) / model.grid->vertex_count(level) >= options.min_support_vertices)
      plan.finest_carrier_level = level;
  const Eigen::MatrixXd c = geometry_coefficients(model, wavelet, plan.coarsest);
  const int end = model.grid->vertex_count(plan.finest_carrier_level);
  KeyedRandom random(key, chip_label("paper", model));
  std::vector<int> order(static_cast<std::size_t>(end));
  for (int k = 0; k < end; ++k) order[k] = k;
  random.shuffle(order);
  for (int i = 0; i < end; ++i) {
    const int k = order[i];
    const double size = c.row(k).norm();
    if (size <= 0) continue;
    const int band = k < model.grid->vertex_count(plan.coarsest) ? 0 : model.grid->level_of(k) - plan.coarsest;
    plan.coefficient.push_back(k);
    plan.bit.push_back(i % payload_bits);
    plan.chip.push_back(random.sign());
    plan.strength.push_back(band == 0 ? std::log1p(size) : std::sqrt(size) / band);
    plan.direction.push_back(c.row(k).transpose() / size);
  }
  return plan;
}

}  // namespace

EmbedResult embed_paper(const PreparedModel& model, const std::string& key, const Bits& payload,
                        const WatermarkOptions& options, const JobControl* control) {
  EmbedResult result;
  StageTimer stages(result.seconds, control);
  stages.start("plan", 0.0);
  const SphericalWavelet wavelet(*model.grid, model.level(), options.wavelet);
  const PaperPlan plan = make_paper_plan(model, wavelet, key, static_cast<int>(payload.size()), options);

  stages.start("synthesis", 0.4);
  Eigen::MatrixXd change = Eigen::MatrixXd::Zero(model.sample_count(), 3);
  for (std::size_t k = 0; k < plan.coefficient.size(); ++k) {
    const double w = plan.chip[k] * (payload[plan.bit[k]] ? 1.0 : -1.0);
    change.row(plan.coefficient[k]) = plan.strength[k] * w * plan.direction[k].transpose();
  }
  wavelet.inverse(change, plan.coarsest);  // the change only: the transform is linear
  const Eigen::MatrixXd move = interpolate_from_grid(*model.grid, model.level(), model.sampling.vertex_cells, change);

  stages.start("apply", 0.8);
  const Eigen::VectorXd length2 = move.rowwise().squaredNorm();
  const double rms = std::sqrt(length2.dot(model.vertex_area) / model.vertex_area.sum());
  const double g = options.strength_percent / 100.0 / rms;  // in units of the diagonal
  result.mesh = model.mesh;
  result.mesh.V += g * model.diagonal * move;
  stages.finish();

  result.carriers = static_cast<int>(plan.coefficient.size());
  for (int level = plan.coarsest; level <= plan.finest_carrier_level; ++level) result.carrier_levels.push_back(level);
  result.coded_bits = static_cast<int>(payload.size());
  result.rms_displacement = options.strength_percent / 100.0;
  result.max_displacement = g * std::sqrt(length2.maxCoeff());
  return result;
}

void detect_paper(const PreparedModel& model, const Displacement& d, const std::string& key,
                  const DetectOptions& options, DetectResult& result) {
  auto t0 = Clock::now();
  const SphericalWavelet wavelet(*model.grid, model.level(), options.watermark.wavelet);
  const PaperPlan plan = make_paper_plan(model, wavelet, key, options.payload_bits, options.watermark);
  const auto n = static_cast<Eigen::Index>(plan.coefficient.size());
  // A: carrier amplitudes along ĉ → synthesized vector change → at the vertices → along n.
  const CarrierEstimator estimator(
      [&](const Eigen::VectorXd& s) -> Eigen::VectorXd {
        Eigen::MatrixXd change = Eigen::MatrixXd::Zero(model.sample_count(), 3);
        for (Eigen::Index k = 0; k < n; ++k) change.row(plan.coefficient[k]) = s[k] * plan.direction[k].transpose();
        wavelet.inverse(change, plan.coarsest);
        const Eigen::MatrixXd move =
            interpolate_from_grid(*model.grid, model.level(), model.sampling.vertex_cells, change);
        return move.cwiseProduct(model.normals).rowwise().sum();
      },
      [&](const Eigen::VectorXd& t) -> Eigen::VectorXd {
        const Faces& F = model.grid->faces[static_cast<std::size_t>(model.level())];
        Eigen::MatrixXd field = Eigen::MatrixXd::Zero(model.sample_count(), 3);
        const auto& cells = model.sampling.vertex_cells;
        for (std::size_t i = 0; i < cells.size(); ++i)
          for (int k = 0; k < 3; ++k)
            field.row(F(cells[i].face, k)) += cells[i].bary[k] * t[static_cast<Eigen::Index>(i)] * model.normals.row(static_cast<Eigen::Index>(i));
        wavelet.inverse_adjoint(field, plan.coarsest);
        Eigen::VectorXd s(n);
        for (Eigen::Index k = 0; k < n; ++k) s[k] = field.row(plan.coefficient[k]).dot(plan.direction[k].transpose());
        return s;
      },
      n);
  const Eigen::VectorXd matched = estimator.matched(d.t);
  result.seconds["filter"] = since(t0);

  t0 = Clock::now();
  // For each estimate and each weighting, every carrier votes chip × amplitude × f^p: p = 1 is
  // the matched weighting when all estimates are equally noisy, p = −1 trusts every carrier
  // alike, p = 0 lies between; which fits depends on the attack, so all three are tried. A payload
  // bit is the sign of its carriers' soft sum; the best-scoring reading is kept.
  Eigen::VectorXd best_vote;
  result.z_score = -std::numeric_limits<double>::infinity();
  constexpr int kPowers[] = {1, 0, -1};
  for (double relative : kRegularizations) {
    const Eigen::VectorXd s = estimator.estimate(matched, relative);
    for (int power : kPowers) {
      Eigen::VectorXd vote(n);
      for (Eigen::Index k = 0; k < n; ++k) vote[k] = plan.chip[k] * s[k] * std::pow(plan.strength[k], power);
      std::vector<double> soft(static_cast<std::size_t>(options.payload_bits), 0.0);
      for (Eigen::Index k = 0; k < n; ++k) soft[plan.bit[k]] += vote[k];
      Bits decoded(soft.size());
      for (std::size_t b = 0; b < soft.size(); ++b) decoded[b] = soft[b] > 0 ? 1 : 0;
      // The statistic: carrier votes against the decoded bits; a Rademacher sum under no watermark.
      double num = 0, den = 0;
      for (Eigen::Index k = 0; k < n; ++k) {
        num += vote[k] * (decoded[plan.bit[k]] ? 1.0 : -1.0);
        den += vote[k] * vote[k];
      }
      const double z = den > 0 ? num / std::sqrt(den) : 0.0;
      if (z > result.z_score) {
        result.z_score = z;
        result.decoded = decoded;
        best_vote = vote;
      }
    }
  }
  const int tries = bits_for_tries(3 * std::size(kRegularizations));  // estimates × vote weightings
  result.blind_log10_p_value = log10_false_alarm_bound(result.z_score, options.payload_bits + tries);
  result.checksum_ok = false;  // the paper's scheme has no checksum: the payload is reported when the mark is present
  if (result.blind_log10_p_value < std::log10(options.false_alarm)) result.payload = result.decoded;
  // The paper's measure: the share of carriers whose bit is read wrongly.
  const Bits& truth = options.expected ? *options.expected : result.decoded;
  std::size_t wrong = 0;
  double num = 0, den = best_vote.squaredNorm();
  for (Eigen::Index k = 0; k < n; ++k) {
    const double sign = truth[plan.bit[k]] ? 1.0 : -1.0;
    wrong += best_vote[k] * sign <= 0;
    num += best_vote[k] * sign;
  }
  result.raw_bit_error_rate = n ? static_cast<double>(wrong) / static_cast<double>(n) : 0.0;
  if (options.expected) {
    result.expected_log10_p_value = log10_false_alarm_bound(den > 0 ? num / std::sqrt(den) : 0.0, tries);
    result.expected_p_value = std::pow(10.0, *result.expected_log10_p_value);
  }
  const int list_bits = bits_for_tries(options.candidates.size());
  for (const Bits& candidate : options.candidates) {
    double c = 0;
    for (Eigen::Index k = 0; k < n; ++k) c += best_vote[k] * (candidate[plan.bit[k]] ? 1.0 : -1.0);
    result.candidate_log10_p.push_back(log10_false_alarm_bound(den > 0 ? c / std::sqrt(den) : 0.0, tries + list_bits));
  }
  result.correlation = den > 0 ? result.z_score / std::sqrt(static_cast<double>(n)) : 0.0;
  result.seconds["decode"] = since(t0);
}

}  // namespace meshmark
