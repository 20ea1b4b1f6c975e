#include "core/watermark/vertex_offsets.hpp"

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <cstdint>

#include "core/mesh/edge_incidence.hpp"
#include "core/spatial/point_index.hpp"
#include "core/util/parallel_for.hpp"

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
std::vector<int> mutual_nearest(const Vertices& original, const Vertices& suspect, double tolerance, int threads) {
  const PointIndex original_index(original), suspect_index(suspect);
  std::vector<int> partner(static_cast<std::size_t>(original.rows()), -1);
  const double limit2 = tolerance * tolerance;
  parallel_for(original.rows(), threads, [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i) {
      const auto [j, d2] = suspect_index.nearest(original.row(i).transpose());
      if (d2 > limit2) continue;
      if (original_index.nearest(suspect.row(j).transpose()).first == i) partner[static_cast<std::size_t>(i)] = j;
    }
  });
  return partner;
}

// A suspect's face edges (its two vertices, lower first) with the face's third vertex, sorted.
struct EdgeThird {
  std::uint64_t edge;
  int third;
  bool operator<(const EdgeThird& other) const {
    return edge < other.edge || (edge == other.edge && third < other.third);
  }
};

std::vector<EdgeThird> edge_thirds(const Faces& F) {
  std::vector<EdgeThird> thirds;
  thirds.reserve(static_cast<std::size_t>(3 * F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) thirds.push_back({edge_key(F(f, k), F(f, (k + 1) % 3)), F(f, (k + 2) % 3)});
  std::sort(thirds.begin(), thirds.end());
  return thirds;
}

// Pairs checked and completed through the faces a reordered copy shares with the original.
// Where a mark moved vertices further than mutual nearest neighbours reach (a dense mesh), some
// are left unpaired or paired with a neighbour's partner. A face maps when its three partners
// make a suspect face; a pair more of whose faces are contradicted than map is dropped, and an
// original face with two paired vertices names the suspect edge between their partners, whose
// free third vertex nearest the original's (within `reach`) pairs it. A copy on other faces
// gains nothing.
class FacePairing {
 public:
  FacePairing(const Mesh& original, const Mesh& aligned, std::vector<int>& partner)
      : original_(original), aligned_(aligned), thirds_(edge_thirds(aligned.F)), partner_(partner) {}

  /// Whether the copy shares the original's faces: more faces map than are contradicted (all
  /// three paired, no such suspect face). A copy stored face by face (split) shares none.
  bool shares_faces() {
    long maps = 0, contradicted = 0;
    for (Eigen::Index f = 0; f < original_.F.rows(); ++f) {
      const FaceState state = face_state(f);
      maps += state == FaceState::maps;
      contradicted += state == FaceState::contradicted;
    }
    return maps > contradicted;
  }

  /// Drops the pairs more of whose faces are contradicted than map (a face cut away is neither).
  void drop_contradicted() {
    std::vector<int> balance(partner_.size(), 0);
    for (Eigen::Index f = 0; f < original_.F.rows(); ++f) {
      const FaceState state = face_state(f);
      if (state == FaceState::unknown) continue;
      for (int k = 0; k < 3; ++k)
        balance[static_cast<std::size_t>(original_.F(f, k))] += state == FaceState::maps ? 1 : -1;
    }
    for (std::size_t v = 0; v < partner_.size(); ++v)
      if (balance[v] < 0) partner_[v] = -1;
  }

  void complete(double reach) {
    std::vector<char> taken(static_cast<std::size_t>(aligned_.V.rows()), 0);
    for (const int j : partner_)
      if (j >= 0) taken[static_cast<std::size_t>(j)] = 1;
    for (bool paired_more = true; paired_more;) {
      paired_more = false;
      for (Eigen::Index f = 0; f < original_.F.rows(); ++f)
        for (int k = 0; k < 3; ++k) {
          const int a = original_.F(f, k), b = original_.F(f, (k + 1) % 3), c = original_.F(f, (k + 2) % 3);
          if (of(a) < 0 || of(b) < 0 || of(c) >= 0) continue;
          const int third = free_third(edge_key(of(a), of(b)), c, reach, taken);
          if (third < 0) continue;
          of(c) = third;
          taken[static_cast<std::size_t>(third)] = 1;
          paired_more = true;
        }
    }
  }

 private:
  int& of(int v) { return partner_[static_cast<std::size_t>(v)]; }

  enum class FaceState { unknown, maps, contradicted };

  FaceState face_state(Eigen::Index f) {
    const int a = of(original_.F(f, 0)), b = of(original_.F(f, 1)), c = of(original_.F(f, 2));
    if (a < 0 || b < 0 || c < 0) return FaceState::unknown;
    return std::binary_search(thirds_.begin(), thirds_.end(), EdgeThird{edge_key(a, b), c}) ? FaceState::maps
                                                                                            : FaceState::contradicted;
  }

  int free_third(std::uint64_t edge, int c, double reach, const std::vector<char>& taken) const {
    int best = -1;
    double best_d2 = reach * reach;
    for (auto it = std::lower_bound(thirds_.begin(), thirds_.end(), EdgeThird{edge, -1});
         it != thirds_.end() && it->edge == edge; ++it) {
      const double d2 = (aligned_.V.row(it->third) - original_.V.row(c)).squaredNorm();
      if (!taken[static_cast<std::size_t>(it->third)] && d2 <= best_d2) best = it->third, best_d2 = d2;
    }
    return best;
  }

  const Mesh& original_;
  const Mesh& aligned_;
  const std::vector<EdgeThird> thirds_;
  std::vector<int>& partner_;
};

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

bool enough_pairs(const std::vector<int>& partner, double min_share) {
  const auto pairs = std::count_if(partner.begin(), partner.end(), [](int j) { return j >= 0; });
  return pairs >= 4 && static_cast<double>(pairs) >= min_share * static_cast<double>(partner.size());
}

// The offsets at the paired vertices, measured on the suspect moved by the pairs' similarity;
// nothing when fewer than `min_share` of the original's vertices are paired.
std::optional<VertexOffsets> offsets_of_pairs(const Vertices& original, const Vertices& suspect,
                                              const std::vector<int>& partner, double min_share) {
  if (!enough_pairs(partner, min_share)) return std::nullopt;
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

std::optional<VertexOffsets> corresponding_offsets(const Mesh& original, const Mesh& aligned, const Vertices& suspect,
                                                   double median_edge, const VertexOffsetOptions& options) {
  if (original.V.rows() == 0 || aligned.V.rows() == 0 || aligned.V.rows() != suspect.rows()) return std::nullopt;
  std::vector<int> partner =
      mutual_nearest(original.V, aligned.V, options.tolerance_edges * median_edge, options.threads);
  // Which copies are read at their vertices is mutual nearest neighbours' call (a smoothed copy
  // shares the faces, but its vertices slid); the faces only mend the pairs of those that are.
  if (!enough_pairs(partner, options.min_share)) return std::nullopt;
  FacePairing faces(original, aligned, partner);
  if (faces.shares_faces()) {
    faces.drop_contradicted();
    faces.complete(options.face_reach_edges * median_edge);
    faces.drop_contradicted();
  }
  return offsets_of_pairs(original.V, suspect, partner, options.min_share);
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
