#include "core/watermark/vertex_offsets.hpp"

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>

#include "core/spatial/point_index.hpp"

namespace meshmark {

double median_edge_length(const Mesh& mesh) {
  std::vector<double> lengths;
  lengths.reserve(static_cast<std::size_t>(3 * mesh.F.rows()));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      lengths.push_back((mesh.V.row(mesh.F(f, k)) - mesh.V.row(mesh.F(f, (k + 1) % 3))).norm());
  if (lengths.empty()) return 0;
  auto middle = lengths.begin() + static_cast<long>(lengths.size() / 2);
  std::nth_element(lengths.begin(), middle, lengths.end());
  return *middle;
}

namespace {

// Per original vertex, the suspect vertex that is its mutual nearest within `tolerance` (or -1).
std::vector<int> mutual_nearest(const Vertices& original, const Vertices& suspect, double tolerance) {
  const PointIndex original_index(original), suspect_index(suspect);
  std::vector<int> partner(static_cast<std::size_t>(original.rows()), -1);
  const double limit2 = tolerance * tolerance;
  for (Eigen::Index i = 0; i < original.rows(); ++i) {
    const auto [j, d2] = suspect_index.nearest(original.row(i).transpose());
    if (d2 > limit2) continue;
    if (original_index.nearest(suspect.row(j).transpose()).first == i) partner[static_cast<std::size_t>(i)] = j;
  }
  return partner;
}

// The similarity that takes the corresponded suspect vertices closest to the original's.
Eigen::Matrix4d pair_similarity(const Vertices& original, const Vertices& suspect, const std::vector<int>& partner) {
  const auto pairs =
      static_cast<Eigen::Index>(std::count_if(partner.begin(), partner.end(), [](int j) { return j >= 0; }));
  Eigen::Matrix3Xd from(3, pairs), to(3, pairs);
  Eigen::Index c = 0;
  for (std::size_t i = 0; i < partner.size(); ++i) {
    if (partner[i] < 0) continue;
    from.col(c) = suspect.row(partner[i]).transpose();
    to.col(c++) = original.row(static_cast<Eigen::Index>(i)).transpose();
  }
  return Eigen::umeyama(from, to, true);
}

// The offsets at the paired vertices, measured on the suspect moved by the pairs' similarity;
// nothing when fewer than `min_share` of the original's vertices are paired.
std::optional<VertexOffsets> offsets_of_pairs(const Vertices& original, const Vertices& suspect,
                                              const std::vector<int>& partner, double min_share) {
  const auto pairs = std::count_if(partner.begin(), partner.end(), [](int j) { return j >= 0; });
  if (pairs < 4 || static_cast<double>(pairs) < min_share * static_cast<double>(original.rows())) return std::nullopt;
  const Eigen::Matrix4d fit = pair_similarity(original, suspect, partner);
  VertexOffsets result{Vertices::Zero(original.rows(), 3), std::vector<char>(partner.size(), 0)};
  for (std::size_t i = 0; i < partner.size(); ++i) {
    if (partner[i] < 0) continue;
    const Eigen::Vector3d moved =
        fit.topLeftCorner<3, 3>() * suspect.row(partner[i]).transpose() + fit.topRightCorner<3, 1>();
    const auto v = static_cast<Eigen::Index>(i);
    result.offset.row(v) = moved.transpose() - original.row(v);
    result.corresponded[i] = 1;
  }
  return result;
}

}  // namespace

std::optional<VertexOffsets> corresponding_offsets(const Vertices& original, const Vertices& aligned,
                                                   const Vertices& suspect, double median_edge,
                                                   const VertexOffsetOptions& options) {
  if (original.rows() == 0 || aligned.rows() == 0 || aligned.rows() != suspect.rows()) return std::nullopt;
  return offsets_of_pairs(original, suspect, mutual_nearest(original, aligned, options.tolerance_edges * median_edge),
                          options.min_share);
}

std::optional<VertexOffsets> offsets_in_order(const Vertices& original, const Vertices& aligned,
                                              const Vertices& suspect, double tolerance,
                                              const VertexOffsetOptions& options) {
  if (original.rows() == 0 || aligned.rows() != original.rows() || suspect.rows() != original.rows())
    return std::nullopt;
  std::vector<int> partner(static_cast<std::size_t>(original.rows()), -1);
  for (Eigen::Index i = 0; i < original.rows(); ++i)
    if ((aligned.row(i) - original.row(i)).norm() <= tolerance)
      partner[static_cast<std::size_t>(i)] = static_cast<int>(i);
  return offsets_of_pairs(original, suspect, partner, options.min_share);
}

Eigen::MatrixXd similarity_fields(const Vertices& original, const std::vector<char>& corresponded) {
  const Eigen::Index n = original.rows();
  const Eigen::RowVector3d centre = original.colwise().mean();
  Eigen::MatrixXd fields = Eigen::MatrixXd::Zero(3 * n, 7);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!corresponded[static_cast<std::size_t>(i)]) continue;
    const Eigen::Vector3d p = (original.row(i) - centre).transpose();
    for (int axis = 0; axis < 3; ++axis) {
      fields(axis * n + i, axis) = 1;  // translation
      const Eigen::Vector3d turn = Eigen::Vector3d::Unit(axis).cross(p);
      for (int k = 0; k < 3; ++k) fields(k * n + i, 3 + axis) = turn[k];
      fields(axis * n + i, 6) = p[axis];  // scale
    }
  }
  return Eigen::HouseholderQR<Eigen::MatrixXd>(fields).householderQ() * Eigen::MatrixXd::Identity(3 * n, 7);
}

}  // namespace meshmark
