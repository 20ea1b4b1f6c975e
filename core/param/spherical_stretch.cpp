#include "core/param/spherical_stretch.hpp"

#include <atomic>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/param/exact_orientation.hpp"
#include "core/param/stretch_face.hpp"
#include "core/util/parallel_for.hpp"

namespace meshmark {

namespace {

using stretch_face::kInfinity;
using stretch_face::Pair;
using stretch_face::PairMask;
using FacePoint = stretch_face::Point<double>;
using PairPoint = stretch_face::Point<Pair>;

FacePoint point_of(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }
PairPoint both_lanes(const Eigen::Vector3d& p) {
  return {Pair::Constant(p.x()), Pair::Constant(p.y()), Pair::Constant(p.z())};
}
stretch_face::Target<double> target_of(const StretchTarget& t) { return {t.mass, t.l[0], t.l[1], t.l[2]}; }

}  // namespace

StretchTarget equilateral_target(double mass) {
  const double side2 = 4.0 / std::sqrt(3.0);  // an equilateral triangle of unit area
  return {mass, {side2, side2, side2}};
}

StretchTarget face_target(const Eigen::Vector3d& q0, const Eigen::Vector3d& q1, const Eigen::Vector3d& q2) {
  const double area = 0.5 * (q1 - q0).cross(q2 - q0).norm();
  const double l0 = (q1 - q2).squaredNorm(), l1 = (q2 - q0).squaredNorm(), l2 = (q0 - q1).squaredNorm();
  if (!(area > 1e-12 * (l0 + l1 + l2))) return equilateral_target(area);  // a sliver keeps no shape worth matching
  return {area, {l0 / area, l1 / area, l2 / area}};
}

double stretch_energy(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                      const StretchTarget& t) {
  const auto e = stretch_face::far_edge(point_of(p1), point_of(p2));
  return stretch_face::energy_at(stretch_face::measure(point_of(p0), e, target_of(t)), t.mass);
}

double stretch_energy_gradient(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                               const StretchTarget& t, Eigen::Vector3d& gradient) {
  const FacePoint at = point_of(p0);
  const auto e = stretch_face::far_edge(point_of(p1), point_of(p2));
  const auto target = target_of(t);
  FacePoint g{};
  const double energy = stretch_face::energy_gradient_at(stretch_face::measure(at, e, target), at, e, target, g);
  gradient = {g.x, g.y, g.z};
  return energy;
}

namespace {

constexpr int kNext[3] = {1, 2, 0}, kAfterNext[3] = {2, 0, 1};

// A colour's vertices per thread at least (a step takes about a microsecond, starting a thread
// tens), and per slice a thread takes at a time.
constexpr std::int64_t kDescentGrain = 512, kDescentSlice = 128;

// A vertex's faces in a StretchProblem, as a star: (vertex, a, b) wound outward.
struct ProblemStar {
  const StretchProblem& problem;
  int begin, end;
  std::size_t size() const { return static_cast<std::size_t>(end - begin); }
  const std::array<int, 2>& others(std::size_t i) const { return face(i).others; }
  const StretchTarget& target(std::size_t i) const { return face(i).target; }
  const StretchProblem::StarFace& face(std::size_t i) const {
    return problem.star[static_cast<std::size_t>(begin) + i];
  }
};

ProblemStar problem_star(const StretchProblem& problem, int v) {
  const auto at = static_cast<std::size_t>(v);
  return {problem, problem.star_offsets[at], problem.star_offsets[at + 1]};
}

// An owned star (VertexStar) seen the same way.
struct OwnedStar {
  const VertexStar& star;
  std::size_t size() const { return star.others.size(); }
  std::array<int, 2> others(std::size_t i) const { return star.others[i]; }
  const StretchTarget& target(std::size_t i) const { return star.targets[i]; }
};

// Two faces of a star side by side, one per lane; when the star's count is odd the last pair's
// second lane repeats its first, and is never read.
struct FacePair {
  stretch_face::FarEdge<Pair> edge;
  stretch_face::Target<Pair> target;
};

// A star's faces with their far edges gathered once, in pairs: the line search evaluates them
// several times, and fetching rows of S by index each time was most of its cost.
struct LocalStar {
  std::vector<FacePair> pairs;
  std::size_t faces = 0;

  template <typename Star>
  void gather(const Vertices& S, const Star& star) {
    faces = star.size();
    pairs.resize((faces + 1) / 2);
    const auto lanes = [&S](int u, int w) {
      return PairPoint{{S(u, 0), S(w, 0)}, {S(u, 1), S(w, 1)}, {S(u, 2), S(w, 2)}};
    };
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const std::size_t first = 2 * i, second = std::min(first + 1, faces - 1);
      const auto o = star.others(first), p = star.others(second);
      const StretchTarget &s = star.target(first), &t = star.target(second);
      pairs[i].edge = stretch_face::far_edge(lanes(o[0], p[0]), lanes(o[1], p[1]));
      pairs[i].target = {{s.mass, t.mass}, {s.l[0], t.l[0]}, {s.l[1], t.l[1]}, {s.l[2], t.l[2]}};
    }
  }
  int lanes_of(std::size_t pair) const { return faces - 2 * pair > 1 ? 2 : 1; }
  // Corner a (or b) of face `face`.
  Eigen::Vector3d corner(std::size_t face, bool b) const {
    const PairPoint& q = b ? pairs[face / 2].edge.b : pairs[face / 2].edge.a;
    const auto lane = static_cast<Eigen::Index>(face % 2);
    return {q.x[lane], q.y[lane], q.z[lane]};
  }
  // Σ |a − p| over the faces, in their order.
  double edge_length_sum(const Eigen::Vector3d& p) const {
    const PairPoint at = both_lanes(p);
    double sum = 0;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const Pair length = stretch_face::squared_distance(pairs[i].edge.a, at).sqrt();
      for (int lane = 0; lane < lanes_of(i); ++lane) sum += length[lane];
    }
    return sum;
  }
  Eigen::Vector3d centre() const {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::size_t f = 0; f < faces; ++f) sum += corner(f, false);
    return sum / static_cast<double>(faces);
  }
};

// The star's energy and gradient along the sphere at x; +∞ when a face is so thin that doubles
// cannot tell its gradient (sin of its smallest angle below ~1e-10): the caller then steps
// towards the star's centre, which any finite energy improves on.
double star_energy_gradient(const LocalStar& star, const Eigen::Vector3d& x, Eigen::Vector3d& g) {
  const PairPoint at = both_lanes(x);
  double energy = 0;
  g.setZero();
  for (std::size_t i = 0; i < star.pairs.size(); ++i) {
    const FacePair& face = star.pairs[i];
    const auto m = stretch_face::measure(at, face.edge, face.target);
    const Pair scale = m.to_a2.max(m.to_b2).max(face.edge.length2);
    const PairMask measurable = m.volume * m.volume > 1e-20 * scale * scale;
    PairPoint gi;
    const Pair face_energy = stretch_face::energy_gradient_at(m, at, face.edge, face.target, gi);
    for (int lane = 0; lane < star.lanes_of(i); ++lane) {
      if (!measurable[lane]) return kInfinity;
      energy += face_energy[lane];
      g += Eigen::Vector3d(gi.x[lane], gi.y[lane], gi.z[lane]);
    }
  }
  g -= g.dot(x) * x;
  return energy;
}

// The energy at x if every face stays positively oriented (decided exactly) and the energy is
// below `bound`, else nullopt. Energies are never negative, so a partial sum that reaches the
// bound decides.
std::optional<double> star_energy_below(const LocalStar& star, const Eigen::Vector3d& x, double bound) {
  const PairPoint at = both_lanes(x);
  double energy = 0;
  for (std::size_t i = 0; i < star.pairs.size(); ++i) {
    const FacePair& face = star.pairs[i];
    const auto m = stretch_face::measure(at, face.edge, face.target);
    const Pair sign_bound = stretch_face::volume_sign_bound(at, face.edge);
    const Pair face_energy = stretch_face::energy_at(m, face.target.mass);
    for (int lane = 0; lane < star.lanes_of(i); ++lane) {
      const double volume = m.volume[lane];
      const bool positive = volume > sign_bound[lane] ||
                            (!(volume < -sign_bound[lane]) && orientation_sign(x, star.corner(2 * i + lane, false),
                                                                               star.corner(2 * i + lane, true)) > 0);
      if (!positive) return std::nullopt;
      energy += face_energy[lane];
      if (!(energy < bound)) return std::nullopt;
    }
  }
  return energy;
}

// One descent step of v over its gathered star (see improve_vertex).
bool step_down(Vertices& S, int v, const LocalStar& star, double& step, const StretchDescentOptions& options) {
  const std::size_t k = star.faces;
  if (k == 0) return false;
  const Eigen::Vector3d p = S.row(v).transpose();
  const double edge_sum = star.edge_length_sum(p);
  Eigen::Vector3d g;
  const double before = star_energy_gradient(star, p, g);
  // Down the gradient along the sphere; where a face is too thin for doubles to measure (its
  // orientation is still exactly positive), towards the star's centre instead.
  Eigen::Vector3d direction = std::isfinite(before) ? Eigen::Vector3d(-g) : Eigen::Vector3d(star.centre() - p);
  direction -= direction.dot(p) * p;
  const double norm = direction.norm();
  if (!(norm > 0) || !direction.allFinite()) return false;
  direction /= norm;
  // A step that shrank to nothing (the vertex was stuck) starts over.
  const double first = options.first_step * edge_sum / static_cast<double>(k);
  if (!(step > first * std::ldexp(1.0, -options.max_halvings))) step = first;
  for (int halving = 0; halving <= options.max_halvings; ++halving, step *= 0.5) {
    const Eigen::Vector3d x = (p + std::min(step, options.max_step) * direction).normalized();
    if (star_energy_below(star, x, before)) {
      S.row(v) = x.transpose();
      step *= 1.5;
      return true;
    }
  }
  return false;
}

template <typename Star>
bool improve(Vertices& S, int v, const Star& source, double& step, const StretchDescentOptions& options) {
  thread_local LocalStar star;
  star.gather(S, source);
  return step_down(S, v, star, step, options);
}

}  // namespace

int improve_vertex(Vertices& S, int v, const VertexStar& star, int steps, const StretchDescentOptions& options) {
  LocalStar local;
  local.gather(S, OwnedStar{star});
  double step = 0;
  int taken = 0;
  while (taken < steps && step_down(S, v, local, step, options)) ++taken;
  return taken;
}

StretchProblem::StretchProblem(const Faces& F, const std::vector<StretchTarget>& targets, Eigen::Index vertex_count,
                               const std::vector<int>& movable) {
  star_offsets.assign(static_cast<std::size_t>(vertex_count) + 1, 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++star_offsets[static_cast<std::size_t>(F(f, k)) + 1];
  for (std::size_t v = 0; v < static_cast<std::size_t>(vertex_count); ++v) star_offsets[v + 1] += star_offsets[v];
  star.resize(static_cast<std::size_t>(3 * F.rows()));
  std::vector<int> fill(star_offsets.begin(), star_offsets.end() - 1);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      star[static_cast<std::size_t>(fill[static_cast<std::size_t>(F(f, k))]++)] = {
          {F(f, kNext[k]), F(f, kAfterNext[k])}, targets[static_cast<std::size_t>(f)].rotated(k)};
  // Greedy colouring in the movable vertices' order: the smallest colour no neighbour has.
  std::vector<int> colour(static_cast<std::size_t>(vertex_count), -1);
  std::vector<char> taken;
  for (const int v : movable) {
    taken.assign(taken.size(), 0);
    for (int i = star_offsets[static_cast<std::size_t>(v)]; i < star_offsets[static_cast<std::size_t>(v) + 1]; ++i) {
      for (const int neighbour : star[static_cast<std::size_t>(i)].others) {
        const int c = colour[static_cast<std::size_t>(neighbour)];
        if (c < 0) continue;
        if (static_cast<std::size_t>(c) >= taken.size()) taken.resize(static_cast<std::size_t>(c) + 1, 0);
        taken[static_cast<std::size_t>(c)] = 1;
      }
    }
    int c = 0;
    while (static_cast<std::size_t>(c) < taken.size() && taken[static_cast<std::size_t>(c)]) ++c;
    colour[static_cast<std::size_t>(v)] = c;
    if (static_cast<std::size_t>(c) >= colours.size()) colours.resize(static_cast<std::size_t>(c) + 1);
    colours[static_cast<std::size_t>(c)].push_back(v);
    if (taken.size() < colours.size()) taken.resize(colours.size(), 0);
  }
  // A colour's vertices are independent, so their order changes no result; in index order they
  // walk S and the stars through memory instead of in the insertion order's random jumps.
  for (std::vector<int>& group : colours) std::sort(group.begin(), group.end());
}

bool step_towards_neighbours(Vertices& S, int v, const StretchProblem& problem) {
  const ProblemStar star = problem_star(problem, v);
  if (star.size() == 0) return false;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < star.size(); ++i) centre += S.row(star.others(i)[0]).transpose();
  centre.normalize();
  const Eigen::Vector3d p = S.row(v).transpose();
  for (double t = 1; t > 1e-3; t *= 0.5) {
    const Eigen::Vector3d x = ((1 - t) * p + t * centre).normalized();
    bool positive = x.allFinite();
    for (std::size_t i = 0; i < star.size() && positive; ++i) {
      const auto o = star.others(i);
      positive = orientation_sign(x, S.row(o[0]).transpose(), S.row(o[1]).transpose()) > 0;
    }
    if (positive) {
      S.row(v) = x.transpose();
      return true;
    }
  }
  return false;
}

StretchDescentResult descend_stretch(Vertices& S, const StretchProblem& problem, std::vector<double>& step,
                                     const StretchDescentOptions& options, const JobControl* control,
                                     const std::function<void(double)>& progress) {
  StretchDescentResult result;
  std::atomic<long long> moves{0}, refused{0};
  const double steps = static_cast<double>(options.sweeps) * static_cast<double>(problem.colours.size());
  double done = 0;
  for (int sweep = 0; sweep < options.sweeps; ++sweep)
    for (const std::vector<int>& group : problem.colours) {
      poll(control);
      if (progress) progress(done++ / steps);
      const auto size = static_cast<std::int64_t>(group.size());
      const int threads = static_cast<int>(std::clamp<std::int64_t>(size / kDescentGrain, 1, threads_of(control)));
      // Slices taken as threads come free: on a host whose cores run at unequal speeds (a VM's
      // cores shared with other tenants), halves fixed in advance wait for the slower core.
      parallel_for_each((size + kDescentSlice - 1) / kDescentSlice, threads, [&](std::int64_t slice) {
        long long moved = 0, stuck = 0;
        for (std::int64_t n = slice * kDescentSlice; n < std::min(size, (slice + 1) * kDescentSlice); ++n) {
          const int v = group[static_cast<std::size_t>(n)];
          if (improve(S, v, problem_star(problem, v), step[static_cast<std::size_t>(v)], options)) ++moved;
          else ++stuck;
        }
        moves += moved;
        refused += stuck;
      });
    }
  result.moves = moves;
  result.refused = refused;
  return result;
}

}  // namespace meshmark
