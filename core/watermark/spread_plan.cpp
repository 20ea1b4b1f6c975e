#include "core/watermark/spread_plan.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/watermark/keyed_random.hpp"
#include "core/watermark/payload_code.hpp"
#include "core/watermark/vertex_field.hpp"

namespace meshmark {

std::string chip_label(const std::string& scheme, const PreparedModel& model) {
  return "meshmark/1/" + scheme + "/" + model.digest;
}

namespace {

// Levels whose bumps are wide enough on the mesh and numerous enough for the code. A grid whose
// levels straddle the threshold (octahedron on a small mesh) falls back to half the width.
std::vector<int> carrier_levels(const PreparedModel& model, int coded, const WatermarkOptions& options) {
  const auto& grid = *model.grid;
  const double vertices = static_cast<double>(model.mesh.V.rows());
  std::vector<int> levels;
  for (double min_support : {options.min_support_vertices, options.min_support_vertices / 2}) {
    for (int level = 1; level <= model.level(); ++level) {
      const double carriers = grid.vertex_count(level) - grid.vertex_count(level - 1);
      const double support = 3.0 * vertices / grid.vertex_count(level);  // a hat covers ~3 vertices' share
      if (support >= min_support && carriers >= options.min_carriers_per_bit * coded) levels.push_back(level);
    }
    if (!levels.empty()) break;
  }
  if (options.max_bands > 0 && static_cast<int>(levels.size()) > options.max_bands)
    levels.erase(levels.begin(), levels.end() - options.max_bands);
  return levels;
}

// Roughness of the original at each grid coefficient: the size of the detail coefficient of
// its geometry, relative to the band's median, square-rooted and kept within [0.5, 2].
Eigen::VectorXd roughness(const PreparedModel& model, const SphericalWavelet& wavelet, const std::vector<int>& levels) {
  Eigen::MatrixXd geometry = model.sampling.positions;
  wavelet.forward(geometry);
  Eigen::VectorXd r = Eigen::VectorXd::Ones(geometry.rows());
  for (int level : levels) {
    const int begin = model.grid->vertex_count(level - 1), end = model.grid->vertex_count(level);
    std::vector<double> size(static_cast<std::size_t>(end - begin));
    for (int k = begin; k < end; ++k) size[k - begin] = geometry.row(k).norm();
    std::vector<double> sorted = size;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
    const double median = std::max(sorted[sorted.size() / 2], 1e-300);
    for (int k = begin; k < end; ++k) r[k] = std::clamp(std::sqrt(size[k - begin] / median), 0.5, 2.0);
  }
  return r;
}

}  // namespace

Eigen::VectorXd plan_coefficients(const SpreadPlan& plan, const std::vector<double>& signs, int rows) {
  Eigen::VectorXd c = Eigen::VectorXd::Zero(rows);
  for (std::size_t k = 0; k < plan.coefficient.size(); ++k) c[plan.coefficient[k]] += plan.weight[k] * signs[plan.bit[k]];
  return c;
}

SpreadPlan make_spread_plan(const PreparedModel& model, const SphericalWavelet& wavelet, const std::string& key,
                            int payload_bits, const WatermarkOptions& options) {
  SpreadPlan plan;
  plan.coded_bits = coded_length(payload_bits);
  plan.levels = carrier_levels(model, plan.coded_bits, options);
  if (plan.levels.empty())
    throw std::invalid_argument("the mesh has too few vertices (" + std::to_string(model.mesh.V.rows()) +
                                ") to carry a " + std::to_string(payload_bits) + "-bit payload; use fewer bits");
  const Eigen::VectorXd rough = roughness(model, wavelet, plan.levels);
  const std::string label = chip_label("spread", model);
  for (std::size_t b = 0; b < plan.levels.size(); ++b) {
    const int level = plan.levels[b];
    std::vector<int> carriers;
    for (int k = model.grid->vertex_count(level - 1); k < model.grid->vertex_count(level); ++k) carriers.push_back(k);
    KeyedRandom random(key, label + "/band/" + std::to_string(level));
    random.shuffle(carriers);
    const auto offset = static_cast<int>(random.below(static_cast<std::uint64_t>(plan.coded_bits)));
    const std::size_t first = plan.coefficient.size();
    for (std::size_t i = 0; i < carriers.size(); ++i) {
      plan.coefficient.push_back(carriers[i]);
      plan.bit.push_back(static_cast<int>((i + static_cast<std::size_t>(offset)) % static_cast<std::size_t>(plan.coded_bits)));
      plan.band.push_back(static_cast<int>(b));
    }
    plan.weight.conservativeResize(static_cast<Eigen::Index>(plan.coefficient.size()));
    for (std::size_t i = first; i < plan.coefficient.size(); ++i) plan.weight[i] = random.sign() * rough[plan.coefficient[i]];
  }
  // Equal energy per band: measure each band's field at the vertices (area-weighted).
  const std::vector<double> ones(static_cast<std::size_t>(plan.coded_bits), 1.0);
  for (std::size_t b = 0; b < plan.levels.size(); ++b) {
    SpreadPlan band_only = plan;
    for (std::size_t i = 0; i < plan.band.size(); ++i)
      if (plan.band[i] != static_cast<int>(b)) band_only.weight[i] = 0;
    const Eigen::VectorXd u =
        coefficients_to_vertices(model, wavelet, plan_coefficients(band_only, ones, model.sample_count()));
    const double energy = u.cwiseProduct(u).dot(model.vertex_area) / model.vertex_area.sum();
    for (std::size_t i = 0; i < plan.band.size(); ++i)
      if (plan.band[i] == static_cast<int>(b)) plan.weight[i] /= std::sqrt(energy);
  }
  return plan;
}

}  // namespace meshmark
