#include "core/watermark/paper_scheme.hpp"

#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>
#include <memory>
#include <optional>

#include "core/watermark/carrier_estimate.hpp"
#include "core/watermark/detect_stages.hpp"
#include "core/watermark/embed_steps.hpp"
#include "core/watermark/known_payload_scores.hpp"
#include "core/util/keyed_random.hpp"
#include "core/watermark/spread_plan.hpp"
#include "core/grid/sample_on_grid.hpp"
#include "core/grid/grid_coverage.hpp"
#include "core/util/stopwatch.hpp"

namespace meshmark {

namespace {

using Clock = std::chrono::steady_clock;

// The carrier estimates detection tries (relative regularization; 0 = the plain matched filter).

// The coarsest level of the decomposition: the approximation band is [0, V_coarsest).
constexpr int kCoarsest = 3;

// A coefficient is a carrier only where the original's vertices see its hat function
// (grid_coverage.hpp) about as much as one vertex at a third of its height ((1/3)² ≈ 0.1): one
// seen less moves almost no vertex, and no reading of the vertices tells its sign.
constexpr double kMinCoverage = 0.1;

struct PaperPlan {
  int coarsest = kCoarsest;
  int finest_carrier_level = 0;
  std::vector<int> coefficient;            // carrier → grid index
  std::vector<int> bit;                    // carrier → payload bit
  std::vector<double> chip;                // carrier → ±1
  std::vector<double> strength;            // carrier → f(c)
  std::vector<Eigen::Vector3d> direction;  // carrier → ĉ
  std::vector<int> band;                   // carrier → 0 (approximation), 1 (coarsest detail), …
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
    if (3.0 * static_cast<double>(model.mesh.V.rows()) / model.grid->vertex_count(level) >=
        options.min_support_vertices)
      plan.finest_carrier_level = level;
  const Eigen::MatrixXd c = geometry_coefficients(model, wavelet, plan.coarsest);
  const int end = model.grid->vertex_count(plan.finest_carrier_level);
  const Eigen::VectorXd coverage = grid_vertex_coverage(*model.grid, model.level(), model.sampling.vertex_cells,
                                                        plan.coarsest, plan.finest_carrier_level);
  KeyedRandom random(key, chip_label("paper", model));
  std::vector<int> order(static_cast<std::size_t>(end));
  for (int k = 0; k < end; ++k) order[k] = k;
  random.shuffle(order);
  for (int i = 0; i < end; ++i) {
    const int k = order[i];
    const double size = c.row(k).norm();
    if (size <= 0 || coverage[k] < kMinCoverage) continue;
    const int band = k < model.grid->vertex_count(plan.coarsest) ? 0 : model.grid->level_of(k) - plan.coarsest;
    plan.coefficient.push_back(k);
    plan.bit.push_back(i % payload_bits);
    plan.chip.push_back(random.sign());
    plan.strength.push_back(band == 0 ? std::log1p(size) : std::sqrt(size) / band);
    plan.direction.push_back(c.row(k).transpose() / size);
    plan.band.push_back(band);
  }
  return plan;
}

// The paper's embedding: each carrier's coefficient moved along its own direction by its
// strength, the change synthesized on the grid and interpolated to the vertices, scaled to the budget.
class PaperEmbedding final : public EmbedSteps {
 public:
  explicit PaperEmbedding(const EmbedInputs& request) : request_(request) {}

  void plan() override {
    wavelet_.emplace(*request_.model.grid, request_.model.level(), request_.options.wavelet);
    plan_ = make_paper_plan(request_.model, *wavelet_, request_.key, static_cast<int>(request_.payload.size()),
                            request_.options);
  }

  void synthesize() override {
    Eigen::MatrixXd change = Eigen::MatrixXd::Zero(request_.model.sample_count(), 3);
    for (std::size_t k = 0; k < plan_.coefficient.size(); ++k) {
      const double w = plan_.chip[k] * (request_.payload[plan_.bit[k]] ? 1.0 : -1.0);
      change.row(plan_.coefficient[k]) = plan_.strength[k] * w * plan_.direction[k].transpose();
    }
    wavelet_->inverse(change, plan_.coarsest);  // the change only: the transform is linear
    move_ = interpolate_from_grid(*request_.model.grid, request_.model.level(), request_.model.sampling.vertex_cells,
                                  change, request_.threads);
  }

  void apply(EmbedResult& result) override {
    length2_ = move_.rowwise().squaredNorm();
    const double rms = std::sqrt(length2_.dot(request_.model.vertex_area) / request_.model.vertex_area.sum());
    gain_ = request_.options.strength_percent / 100.0 / rms;  // in units of the diagonal
    result.mesh = request_.model.mesh;
    result.mesh.V += gain_ * request_.model.diagonal * move_;
  }

  void describe(EmbedResult& result) const override {
    result.carriers = static_cast<int>(plan_.coefficient.size());
    for (int level = plan_.coarsest; level <= plan_.finest_carrier_level; ++level)
      result.carrier_levels.push_back(level);
    result.coded_bits = static_cast<int>(request_.payload.size());
    result.rms_displacement = request_.options.strength_percent / 100.0;
    result.max_displacement = gain_ * std::sqrt(length2_.maxCoeff());
  }

 private:
  const EmbedInputs request_;
  std::optional<SphericalWavelet> wavelet_;
  PaperPlan plan_;
  Eigen::MatrixXd move_;  // the unscaled change at each vertex (#V × 3)
  Eigen::VectorXd length2_;
  double gain_ = 0;
};

}  // namespace

EmbedResult embed_paper(const PreparedModel& model, const std::string& key, const Bits& payload,
                        const WatermarkOptions& options, const JobControl* control) {
  PaperEmbedding steps({model, key, payload, options, threads_of(control)});
  return run_embed_steps(steps, control);
}

namespace {

// Carrier amplitudes along ĉ → the synthesized vector change at the vertices (#V×3).
Eigen::MatrixXd change_at_vertices(const PreparedModel& model, const SphericalWavelet& wavelet, const PaperPlan& plan,
                                   const Eigen::VectorXd& s, int threads) {
  Eigen::MatrixXd change = Eigen::MatrixXd::Zero(model.sample_count(), 3);
  for (Eigen::Index k = 0; k < s.size(); ++k) change.row(plan.coefficient[k]) = s[k] * plan.direction[k].transpose();
  wavelet.inverse(change, plan.coarsest);
  return interpolate_from_grid(*model.grid, model.level(), model.sampling.vertex_cells, change, threads);
}

// The adjoint of change_at_vertices: vectors at the vertices → one value per carrier.
Eigen::VectorXd carriers_of_change(const PreparedModel& model, const SphericalWavelet& wavelet, const PaperPlan& plan,
                                   const Eigen::MatrixXd& at_vertices) {
  const Faces& F = model.grid->faces[static_cast<std::size_t>(model.level())];
  Eigen::MatrixXd field = Eigen::MatrixXd::Zero(model.sample_count(), 3);
  const auto& cells = model.sampling.vertex_cells;
  for (std::size_t i = 0; i < cells.size(); ++i)
    for (int k = 0; k < 3; ++k)
      field.row(F(cells[i].face, k)) += cells[i].bary[k] * at_vertices.row(static_cast<Eigen::Index>(i));
  wavelet.inverse_adjoint(field, plan.coarsest);
  Eigen::VectorXd s(static_cast<Eigen::Index>(plan.coefficient.size()));
  for (Eigen::Index k = 0; k < s.size(); ++k) s[k] = field.row(plan.coefficient[k]).dot(plan.direction[k].transpose());
  return s;
}

// A linear model of a reading: A (carrier amplitudes → measurements), Aᵀ, and the measurements.
struct PaperReadingModel {
  LinearMap forward, adjoint;
  Eigen::VectorXd measured;
};

// A: carrier amplitudes → the change along each vertex's normal; and Aᵀ.
PaperReadingModel normal_reading(const PreparedModel& model, const SphericalWavelet& wavelet, const PaperPlan& plan,
                                 const Displacement& d, int threads) {
  return {[&model, &wavelet, &plan, threads](const Eigen::VectorXd& s) -> Eigen::VectorXd {
            return change_at_vertices(model, wavelet, plan, s, threads).cwiseProduct(model.normals).rowwise().sum();
          },
          [&model, &wavelet, &plan](const Eigen::VectorXd& t) -> Eigen::VectorXd {
            return carriers_of_change(model, wavelet, plan, model.normals.array().colwise() * t.array());
          },
          d.t};
}

// The rows of V as one vector, as a column-major #V×3 matrix stores them.
Eigen::VectorXd column_major(const Vertices& V) {
  const Eigen::MatrixXd columns = V;
  return Eigen::Map<const Eigen::VectorXd>(columns.data(), columns.size());
}

// A: carrier amplitudes → the whole change at the corresponded vertices (column-major #V×3 as
// one vector, 0 elsewhere), less its part a small similarity could make; and Aᵀ. The paper's
// carriers move vertices along ĉ, mostly off the normal: this reads them as the paper does. The
// similarity is taken from model and measurement alike, so the coarse carriers' share of it
// is not read as misregistration.
PaperReadingModel vector_reading(const PreparedModel& model, const SphericalWavelet& wavelet, const PaperPlan& plan,
                                 const VertexOffsets& offsets, int threads) {
  Eigen::VectorXd mask(static_cast<Eigen::Index>(offsets.corresponded.size()));
  for (std::size_t i = 0; i < offsets.corresponded.size(); ++i)
    mask[static_cast<Eigen::Index>(i)] = offsets.corresponded[i] ? 1 : 0;
  auto similarity = std::make_shared<const Eigen::MatrixXd>(similarity_fields(model.mesh.V, offsets.corresponded));
  auto project = [similarity](Eigen::VectorXd t) -> Eigen::VectorXd {
    t -= *similarity * (similarity->transpose() * t);
    return t;
  };
  const Eigen::Index rows = mask.size();
  return {[&model, &wavelet, &plan, mask, project, threads](const Eigen::VectorXd& s) -> Eigen::VectorXd {
            const Eigen::MatrixXd change =
                change_at_vertices(model, wavelet, plan, s, threads).array().colwise() * mask.array();
            return project(Eigen::Map<const Eigen::VectorXd>(change.data(), change.size()));
          },
          [&model, &wavelet, &plan, mask, project, rows](const Eigen::VectorXd& t) -> Eigen::VectorXd {
            const Eigen::VectorXd kept = project(t);
            const Eigen::MatrixXd at_vertices =
                Eigen::Map<const Eigen::MatrixXd>(kept.data(), rows, 3).array().colwise() * mask.array();
            return carriers_of_change(model, wavelet, plan, at_vertices);
          },
          project(column_major(offsets.offset))};
}

// The vector reading where the suspect's vertices correspond to the original's, else the normal one.
PaperReadingModel paper_reading_model(const PreparedModel& model, const SphericalWavelet& wavelet,
                                      const PaperPlan& plan, const Displacement& d, int threads) {
  return d.vertex_offsets ? vector_reading(model, wavelet, plan, *d.vertex_offsets, threads)
                          : normal_reading(model, wavelet, plan, d, threads);
}

struct PaperReading {
  Eigen::VectorXd vote;  ///< per carrier: chip × estimated amplitude × strength^p
  Bits decoded;
  double z = -std::numeric_limits<double>::infinity();
};

// For each estimate and each weighting, every carrier votes chip × amplitude × f^p: p = 1 is the
// matched weighting when all estimates are equally noisy, p = −1 trusts every carrier alike, p = 0
// lies between; which fits depends on the attack, so all three are tried. A payload bit is the
// sign of its carriers' soft sum; the best-scoring reading is kept.
constexpr int kVotePowers[] = {1, 0, -1};

PaperReading choose_paper_reading(const PaperPlan& plan, const std::vector<Eigen::VectorXd>& estimates,
                                  int payload_bits) {
  const auto n = static_cast<Eigen::Index>(plan.coefficient.size());
  PaperReading best;
  for (const Eigen::VectorXd& s : estimates) {
    for (int power : kVotePowers) {
      Eigen::VectorXd vote(n);
      for (Eigen::Index k = 0; k < n; ++k) vote[k] = plan.chip[k] * s[k] * std::pow(plan.strength[k], power);
      std::vector<double> soft(static_cast<std::size_t>(payload_bits), 0.0);
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
      if (z > best.z) best = {vote, decoded, z};
    }
  }
  return best;
}

DetectResult score_paper_reading(const PaperReading& best, const PaperPlan& plan, const DetectOptions& options) {
  DetectResult result;
  const auto n = static_cast<Eigen::Index>(plan.coefficient.size());
  result.z_score = best.z;
  result.decoded = best.decoded;
  const int tries = bits_for_tries(std::size(kVotePowers) * options.estimate.charged(std::max(
                                                                options.estimate.paper_regularizations.size(),
                                                                options.estimate.paper_vector_regularizations.size())));
  result.blind_log10_p_value = log10_false_alarm_bound(result.z_score, options.payload_bits + tries);
  result.checksum_ok = false;  // the paper's scheme has no checksum: the payload is reported when the mark is present
  if (result.blind_log10_p_value < std::log10(options.false_alarm)) result.payload = result.decoded;
  // The paper's measure: the share of carriers whose bit is read wrongly.
  const Bits& truth = options.expected ? *options.expected : result.decoded;
  std::size_t wrong = 0;
  for (Eigen::Index k = 0; k < n; ++k) wrong += best.vote[k] * (truth[plan.bit[k]] ? 1.0 : -1.0) <= 0;
  result.raw_bit_error_rate = n ? static_cast<double>(wrong) / static_cast<double>(n) : 0.0;
  const double norm2 = best.vote.squaredNorm();
  score_known_payloads(options, tries, [&](const Bits& payload) {
    return vote_statistic(best.vote, plan.bit, signs_of(payload), norm2);
  }).write_to(result);
  result.correlation = norm2 > 0 ? result.z_score / std::sqrt(static_cast<double>(n)) : 0.0;
  return result;
}

}  // namespace

DetectResult detect_paper(const PreparedModel& model, const Displacement& d, const std::string& key,
                          const DetectOptions& options, const JobControl* control) {
  auto t0 = Clock::now();
  const SphericalWavelet wavelet(*model.grid, model.level(), options.watermark.wavelet);
  const PaperPlan plan = make_paper_plan(model, wavelet, key, options.payload_bits, options.watermark);
  const auto carriers = static_cast<Eigen::Index>(plan.coefficient.size());
  const PaperReadingModel reading = paper_reading_model(model, wavelet, plan, d, threads_of(control));
  // The vector reading solves near convergence: preconditioned by band, whose scales differ most.
  const CarrierEstimator estimator = d.vertex_offsets ? CarrierEstimator(reading.forward, reading.adjoint, carriers,
                                                                         options.estimate.paper_vector_solve, plan.band)
                                                      : CarrierEstimator(reading.forward, reading.adjoint, carriers);
  const Eigen::VectorXd matched = estimator.matched(reading.measured);
  const std::vector<Eigen::VectorXd> estimates =
      estimator.estimates(matched, d.vertex_offsets ? options.estimate.paper_vector_regularizations
                                                    : options.estimate.paper_regularizations);
  const double estimate_seconds = seconds_since(t0);
  checkpoint(control, detect_stage::decode, 0.8);
  t0 = Clock::now();
  DetectResult result = score_paper_reading(choose_paper_reading(plan, estimates, options.payload_bits), plan, options);
  result.seconds[detect_stage::estimate] = estimate_seconds;
  result.seconds[detect_stage::decode] = seconds_since(t0);
  return result;
}

}  // namespace meshmark
