#include "core/param/spherical_stretch.hpp"

#include <atomic>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/param/exact_orientation.hpp"
#include "core/util/parallel_for.hpp"

namespace meshmark {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// atan2(y, x) for x > 0: by its series when |y/x| < 0.1 (the faces of any fine mesh; the error
// is below 1e-10 of the value), where atan2 itself was a fifth of the descent's time.
double angle_of(double y, double x) {
  if (x > 0) {
    const double t = y / x;
    if (std::abs(t) < 0.1) {
      const double t2 = t * t;
      return t * (1 - t2 * (1.0 / 3 - t2 * (1.0 / 5 - t2 * (1.0 / 7))));
    }
  }
  return std::atan2(y, x);
}

struct Measures {
  double N = 0, D = 0;
  double volume = 0, w = 0, area = 0;  // det(p0, p1, p2); 1 + Σ pi·pj; the spherical area
};

Measures measure(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                 const StretchTarget& t) {
  Measures m;
  const double m0 = (p1 - p2).squaredNorm(), m1 = (p2 - p0).squaredNorm(), m2 = (p0 - p1).squaredNorm();
  const double sum_l = t.l[0] + t.l[1] + t.l[2];
  m.N = 0.5 * (sum_l * (m0 + m1 + m2) - 2 * (t.l[0] * m0 + t.l[1] * m1 + t.l[2] * m2));
  // D = 4·(spherical area)², by Van Oosterom and Strackee's formula, rather than the chord
  // triangle's |(p1 − p0) × (p2 − p0)|²: the two agree for small triangles, but only the spherical
  // area vanishes when a large triangle degenerates (its corners on one great circle) and stays
  // right at the scale of a tetrahedron's faces.
  m.volume = p0.dot(p1.cross(p2));
  m.w = 1 + p0.dot(p1) + p1.dot(p2) + p2.dot(p0);
  m.area = 2 * angle_of(m.volume, m.w);
  m.D = 4 * m.area * m.area;
  return m;
}

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

// E = m² · √2/2 · N^¼ · D^(−5/8), by square roots.
double energy_of(const Measures& m, double mass) {
  const double root_d = std::sqrt(m.D), eighth_d = std::sqrt(std::sqrt(root_d));
  return 0.5 * std::sqrt(2.0) * mass * mass * std::sqrt(std::sqrt(m.N)) / (root_d * eighth_d);
}

double stretch_energy(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                      const StretchTarget& t) {
  const Measures m = measure(p0, p1, p2, t);
  if (!(m.area > 0) || !(m.N > 0)) return kInfinity;
  return energy_of(m, t.mass);
}

double stretch_energy_gradient(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                               const StretchTarget& t, Eigen::Vector3d& gradient) {
  const Measures m = measure(p0, p1, p2, t);
  if (!(m.area > 0)) {
    gradient.setZero();
    return kInfinity;
  }
  // ∇N = (l0 + l2 − l1)(p0 − p2) + (l0 + l1 − l2)(p0 − p1);  ∇D = 8A ∇A, with
  // ∇A = 2 (w ∇det − det ∇w) / (det² + w²), ∇det = p1 × p2, ∇w = p1 + p2.
  const Eigen::Vector3d dN = (t.l[0] + t.l[2] - t.l[1]) * (p0 - p2) + (t.l[0] + t.l[1] - t.l[2]) * (p0 - p1);
  const Eigen::Vector3d dA = 2 * (m.w * p1.cross(p2) - m.volume * (p1 + p2)) / (m.volume * m.volume + m.w * m.w);
  const Eigen::Vector3d dD = 8 * m.area * dA;
  if (!(m.N > 0)) {
    gradient.setZero();
    return kInfinity;
  }
  const double E = energy_of(m, t.mass);
  gradient = E * (0.25 * dN / m.N - 0.625 * dD / m.D);
  return E;
}

namespace {

constexpr int kNext[3] = {1, 2, 0}, kAfterNext[3] = {2, 0, 1};

// A vertex's faces in a StretchProblem, as a star: (vertex, a, b) wound outward.
struct ProblemStar {
  const StretchProblem& problem;
  int begin, end;
  std::size_t size() const { return static_cast<std::size_t>(end - begin); }
  std::array<int, 2> others(std::size_t i) const {
    const auto [f, corner] = problem.star[static_cast<std::size_t>(begin) + i];
    return {problem.F(f, kNext[corner]), problem.F(f, kAfterNext[corner])};
  }
  StretchTarget target(std::size_t i) const {
    const auto [f, corner] = problem.star[static_cast<std::size_t>(begin) + i];
    return problem.targets[static_cast<std::size_t>(f)].rotated(corner);
  }
};

// An owned star (VertexStar) seen the same way.
struct OwnedStar {
  const VertexStar& star;
  std::size_t size() const { return star.others.size(); }
  std::array<int, 2> others(std::size_t i) const { return star.others[i]; }
  const StretchTarget& target(std::size_t i) const { return star.targets[i]; }
};

// A star's faces with their far corners' positions gathered once: the line search evaluates
// them several times, and fetching rows of S by index each time was most of its cost.
struct LocalStar {
  std::vector<Eigen::Vector3d> a, b;
  std::vector<StretchTarget> targets;

  template <typename Star>
  void gather(const Vertices& S, const Star& star) {
    const std::size_t k = star.size();
    a.resize(k);
    b.resize(k);
    targets.resize(k);
    for (std::size_t i = 0; i < k; ++i) {
      const auto o = star.others(i);
      a[i] = S.row(o[0]).transpose();
      b[i] = S.row(o[1]).transpose();
      targets[i] = star.target(i);
    }
  }
  std::size_t size() const { return a.size(); }
};

// The star's energy and gradient along the sphere at x; +∞ when a face is so thin that doubles
// cannot tell its gradient (sin of its smallest angle below ~1e-10): the caller then steps
// towards the star's centre, which any finite energy improves on.
double star_energy_gradient(const LocalStar& star, const Eigen::Vector3d& x, Eigen::Vector3d& g) {
  double energy = 0;
  g.setZero();
  for (std::size_t i = 0; i < star.size(); ++i) {
    const Eigen::Vector3d& a = star.a[i];
    const Eigen::Vector3d& b = star.b[i];
    const double scale = std::max({(a - x).squaredNorm(), (b - x).squaredNorm(), (b - a).squaredNorm()});
    const double volume = x.dot(a.cross(b));
    if (!(volume * volume > 1e-20 * scale * scale)) return std::numeric_limits<double>::infinity();
    Eigen::Vector3d gi;
    energy += stretch_energy_gradient(x, a, b, star.targets[i], gi);
    g += gi;
  }
  g -= g.dot(x) * x;
  return energy;
}

// The energy at x if every face stays positively oriented (decided exactly), else nullopt.
std::optional<double> star_energy_if_positive(const LocalStar& star, const Eigen::Vector3d& x) {
  double energy = 0;
  for (std::size_t i = 0; i < star.size(); ++i) {
    if (orientation_sign(x, star.a[i], star.b[i]) <= 0) return std::nullopt;
    energy += stretch_energy(x, star.a[i], star.b[i], star.targets[i]);
  }
  return energy;
}

template <typename Star>
bool improve(Vertices& S, int v, const Star& source, double& step, const StretchDescentOptions& options) {
  thread_local LocalStar star;
  star.gather(S, source);
  const std::size_t k = star.size();
  if (k == 0) return false;
  const Eigen::Vector3d p = S.row(v).transpose();
  double edge_sum = 0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < k; ++i) {
    centre += star.a[i];
    edge_sum += (star.a[i] - p).norm();
  }
  Eigen::Vector3d g;
  const double before = star_energy_gradient(star, p, g);
  // Down the gradient along the sphere; where a face is too thin for doubles to measure (its
  // orientation is still exactly positive), towards the star's centre instead.
  Eigen::Vector3d direction = std::isfinite(before) ? Eigen::Vector3d(-g) : Eigen::Vector3d(centre / k - p);
  direction -= direction.dot(p) * p;
  const double norm = direction.norm();
  if (!(norm > 0) || !direction.allFinite()) return false;
  direction /= norm;
  // A step that shrank to nothing (the vertex was stuck) starts over.
  const double first = options.first_step * edge_sum / static_cast<double>(k);
  if (!(step > first * std::ldexp(1.0, -options.max_halvings))) step = first;
  for (int halving = 0; halving <= options.max_halvings; ++halving, step *= 0.5) {
    const Eigen::Vector3d x = (p + std::min(step, options.max_step) * direction).normalized();
    const auto after = star_energy_if_positive(star, x);
    if (after && *after < before) {
      S.row(v) = x.transpose();
      step *= 1.5;
      return true;
    }
  }
  return false;
}

}  // namespace

bool improve_vertex(Vertices& S, int v, const VertexStar& star, double& step, const StretchDescentOptions& options) {
  return improve(S, v, OwnedStar{star}, step, options);
}

StretchProblem::StretchProblem(const Faces& faces, std::vector<StretchTarget> face_targets, Eigen::Index vertex_count,
                               const std::vector<int>& movable)
    : F(faces), targets(std::move(face_targets)) {
  star_offsets.assign(static_cast<std::size_t>(vertex_count) + 1, 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++star_offsets[static_cast<std::size_t>(F(f, k)) + 1];
  for (std::size_t v = 0; v < static_cast<std::size_t>(vertex_count); ++v) star_offsets[v + 1] += star_offsets[v];
  star.resize(static_cast<std::size_t>(3 * F.rows()));
  std::vector<int> fill(star_offsets.begin(), star_offsets.end() - 1);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      star[static_cast<std::size_t>(fill[static_cast<std::size_t>(F(f, k))]++)] = {static_cast<int>(f), k};
  // Greedy colouring in the movable vertices' order: the smallest colour no neighbour has.
  std::vector<int> colour(static_cast<std::size_t>(vertex_count), -1);
  std::vector<char> taken;
  for (const int v : movable) {
    taken.assign(taken.size(), 0);
    for (int i = star_offsets[static_cast<std::size_t>(v)]; i < star_offsets[static_cast<std::size_t>(v) + 1]; ++i) {
      const auto [f, corner] = star[static_cast<std::size_t>(i)];
      for (int k = 1; k < 3; ++k) {
        const int c = colour[static_cast<std::size_t>(F(f, (corner + k) % 3))];
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
}

bool step_towards_neighbours(Vertices& S, int v, const StretchProblem& problem) {
  const ProblemStar star{problem, problem.star_offsets[static_cast<std::size_t>(v)],
                         problem.star_offsets[static_cast<std::size_t>(v) + 1]};
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
      parallel_for(
          static_cast<std::int64_t>(group.size()), threads_of(control),
          [&](std::int64_t begin, std::int64_t end) {
            long long moved = 0, stuck = 0;
            for (std::int64_t n = begin; n < end; ++n) {
              const int v = group[static_cast<std::size_t>(n)];
              const ProblemStar star{problem, problem.star_offsets[static_cast<std::size_t>(v)],
                                     problem.star_offsets[static_cast<std::size_t>(v) + 1]};
              if (improve(S, v, star, step[static_cast<std::size_t>(v)], options)) ++moved;
              else ++stuck;
            }
            moves += moved;
            refused += stuck;
          },
          512);
    }
  result.moves = moves;
  result.refused = refused;
  return result;
}

}  // namespace meshmark
