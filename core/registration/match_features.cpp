#include "core/registration/match_features.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/mesh/massmatrix.hpp"
#include "core/mesh/vertex_normals.hpp"
#include "core/metrics/compare_meshes.hpp"
#include "core/spatial/point_index.hpp"
#include "core/util/parallel_for.hpp"

namespace meshmark {

namespace {

constexpr int kDescriptorSize = 3 * kFeatureBins;
using HistogramRow = Eigen::Ref<Eigen::RowVectorXd, 0, Eigen::InnerStride<>>;

int bin_of(double value, double low, double high) {
  const auto b = static_cast<int>((value - low) / (high - low) * kFeatureBins);
  return std::clamp(b, 0, kFeatureBins - 1);
}

// The three angles between the surface at `p` (normal `n`) and at `q` (normal `m`), in the
// Darboux frame at p, without the normals' signs: the cosine between the frame's second axis
// and m, the cosine between n and the direction to q, and the turn of m about that direction.
void add_pair(const Eigen::Vector3d& p, const Eigen::Vector3d& n, const Eigen::Vector3d& q, Eigen::Vector3d m,
              HistogramRow histogram) {
  const Eigen::Vector3d d = q - p;
  const double length = d.norm();
  if (!(length > 0) || n.squaredNorm() == 0 || m.squaredNorm() == 0) return;
  const Eigen::Vector3d direction = d / length;
  if (m.dot(n) < 0) m = -m;  // the two normals on one side: flipping n then flips both
  const Eigen::Vector3d v = direction.cross(n);
  if (v.norm() < 1e-12) return;
  const Eigen::Vector3d v_unit = v.normalized(), w = n.cross(v_unit);
  histogram(bin_of(v_unit.dot(m), -1, 1)) += 1;
  histogram(kFeatureBins + bin_of(std::abs(n.dot(direction)), 0, 1)) += 1;
  histogram(2 * kFeatureBins + bin_of(std::abs(std::atan2(w.dot(m), n.dot(m))), 0, M_PI)) += 1;
}

// Each histogram of the row scaled to sum 1 (an empty one stays empty).
void normalize_histograms(HistogramRow row) {
  for (int h = 0; h < 3; ++h) {
    auto block = row.segment(h * kFeatureBins, kFeatureBins);
    const double sum = block.sum();
    if (sum > 0) block /= sum;
  }
}

}  // namespace

// Per point: its own histograms of the angles to its neighbours, then (FPFH) those of the
// neighbours added in, nearer ones weighing more.
Eigen::MatrixXd describe_points(const Vertices& P, const Vertices& N, int neighbours, int threads) {
  const PointIndex index(P);
  const Eigen::Index n = P.rows();
  std::vector<std::vector<std::pair<int, double>>> near(static_cast<std::size_t>(n));
  Eigen::MatrixXd own = Eigen::MatrixXd::Zero(n, kDescriptorSize);
  parallel_for(n, threads, [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i) {
      auto& ring = near[static_cast<std::size_t>(i)];
      ring = index.nearest_k(P.row(i).transpose(), neighbours + 1);
      std::erase_if(ring, [&](const std::pair<int, double>& q) { return q.first == i || q.second == 0; });
      for (const auto& [j, distance_squared] : ring)
        add_pair(P.row(i).transpose(), N.row(i).transpose(), P.row(j).transpose(), N.row(j).transpose(), own.row(i));
      normalize_histograms(own.row(i));
    }
  });
  Eigen::MatrixXd out = own;
  parallel_for(n, threads, [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i) {
      const auto& ring = near[static_cast<std::size_t>(i)];
      if (ring.empty()) continue;
      Eigen::RowVectorXd spread = Eigen::RowVectorXd::Zero(kDescriptorSize);
      double total = 0;
      for (const auto& [j, distance_squared] : ring) {
        const double weight = 1 / std::sqrt(distance_squared);
        spread += weight * own.row(j);
        total += weight;
      }
      out.row(i) += spread / total;
      normalize_histograms(out.row(i));
    }
  });
  return out;
}

namespace {

// Unit normals of the faces the points lie on (zero on a degenerate face: it describes nothing).
Vertices normals_at(const Mesh& mesh, const std::vector<int>& faces) {
  const Vertices face_normal = face_normals(mesh.V, mesh.F);
  Vertices out(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const Eigen::RowVector3d normal = face_normal.row(faces[i]);
    out.row(static_cast<Eigen::Index>(i)) = normal.allFinite() ? normal : Eigen::RowVector3d::Zero();
  }
  return out;
}

double surface_area(const Mesh& mesh) { return mesh.F.rows() == 0 ? 0 : face_areas(mesh.V, mesh.F).sum(); }

// Each side's nearest row on the other, by descriptor distance.
struct NearestRows {
  std::vector<int> original_of, suspect_of;
  std::vector<double> to_original;  // distance from each original row to its nearest suspect row
};

// Takes in the squared distances of suspect rows first.. (a block) to every original row: one
// pass down each column, where the memory runs.
void take_block(const Eigen::MatrixXd& distance, Eigen::Index first, NearestRows& nearest) {
  std::vector<double> to_suspect(static_cast<std::size_t>(distance.rows()), std::numeric_limits<double>::infinity());
  for (Eigen::Index j = 0; j < distance.cols(); ++j) {
    const double* column = distance.col(j).data();
    const auto o = static_cast<std::size_t>(j);
    for (Eigen::Index r = 0; r < distance.rows(); ++r) {
      const auto s = static_cast<std::size_t>(r);
      if (column[r] < nearest.to_original[o])
        nearest.to_original[o] = column[r], nearest.suspect_of[o] = static_cast<int>(first + r);
      if (column[r] < to_suspect[s])
        to_suspect[s] = column[r], nearest.original_of[static_cast<std::size_t>(first + r)] = static_cast<int>(j);
    }
  }
}

// Matches of suspect rows to original rows whose descriptors are each other's nearest. By blocks
// of squared distances |s|² + |o|² − 2 s·o, a matrix product: in 33 dimensions a k-d tree visits
// most of its leaves (it took a fifth of a detection's time).
std::vector<PointMatch> mutual_matches(const ShapeFeatures& suspect, const ShapeFeatures& original) {
  const Eigen::MatrixXd &S = suspect.descriptors, &O = original.descriptors;
  const Eigen::RowVectorXd original_norms = O.rowwise().squaredNorm().transpose();
  NearestRows nearest{std::vector<int>(static_cast<std::size_t>(S.rows()), -1),
                      std::vector<int>(static_cast<std::size_t>(O.rows()), -1),
                      std::vector<double>(static_cast<std::size_t>(O.rows()), std::numeric_limits<double>::infinity())};
  constexpr Eigen::Index kBlock = 512;
  for (Eigen::Index first = 0; first < S.rows(); first += kBlock) {
    const Eigen::Index rows = std::min(kBlock, S.rows() - first);
    Eigen::MatrixXd distance = -2 * S.middleRows(first, rows) * O.transpose();
    distance.rowwise() += original_norms;
    distance.colwise() += S.middleRows(first, rows).rowwise().squaredNorm();
    take_block(distance, first, nearest);
  }
  std::vector<PointMatch> matches;
  for (Eigen::Index j = 0; j < O.rows(); ++j) {
    const int i = nearest.suspect_of[static_cast<std::size_t>(j)];
    if (i >= 0 && nearest.original_of[static_cast<std::size_t>(i)] == j)
      matches.push_back({suspect.points.row(i).transpose(), original.points.row(j).transpose(), static_cast<int>(j)});
  }
  return matches;
}

}  // namespace

ShapeFeatures::ShapeFeatures(const Mesh& mesh, Eigen::Index count, int neighbours, int threads)
    : area(surface_area(mesh)) {
  std::vector<int> faces;
  points = sample_surface(mesh, static_cast<std::size_t>(std::max<Eigen::Index>(count, 0)), &faces);
  descriptors = describe_points(points, normals_at(mesh, faces), neighbours, threads);
}

std::vector<Similarity> match_features(const Mesh& suspect, double scale_guess, const ShapeFeatures& original,
                                       const FeatureOptions& options, const JobControl* control) {
  if (original.points.rows() <= options.neighbours || !(original.area > 0)) return {};
  // As densely per area as the original's points, the suspect's area taken at the guessed scale.
  const double scaled_area = surface_area(suspect) * scale_guess * scale_guess;
  const double wanted = static_cast<double>(original.points.rows()) * scaled_area / original.area;
  const auto count = static_cast<Eigen::Index>(std::clamp(wanted, static_cast<double>(options.min_suspect_points),
                                                          static_cast<double>(options.max_suspect_points)));
  poll(control);
  const ShapeFeatures features(suspect, count, options.neighbours, threads_of(control));
  poll(control);
  const std::vector<PointMatch> matches = mutual_matches(features, original);
  const double spacing = std::sqrt(original.area / static_cast<double>(original.points.rows()));
  return vote_poses(matches, static_cast<std::size_t>(original.points.rows()), options.tolerance_spacings * spacing,
                    options.vote, control);
}

}  // namespace meshmark
