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

// A face's edge opposite the moving corner, with what does not depend on that corner: the line
// search evaluates a star's faces several times at new positions of the one vertex.
struct FarEdge {
  Eigen::Vector3d a, b, a_cross_b;
  double a_dot_b = 0, length2 = 0;  // a·b, |a − b|²
  double cross_bound[3] = {};       // |a_j b_k| + |a_k b_j|: bounds the rounding of a × b

  FarEdge() = default;
  FarEdge(const Eigen::Vector3d& a_in, const Eigen::Vector3d& b_in)
      : a(a_in), b(b_in), a_cross_b(a_in.cross(b_in)), a_dot_b(a_in.dot(b_in)), length2((a_in - b_in).squaredNorm()) {
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      cross_bound[i] = std::abs(a[j] * b[k]) + std::abs(a[k] * b[j]);
    }
  }
};

struct Measures {
  double N = 0, D = 0;
  double volume = 0, w = 0, area = 0;  // det(p0, p1, p2); 1 + Σ pi·pj; the spherical area
  double to_b2 = 0, to_a2 = 0;         // |p2 − p0|², |p0 − p1|²
};

Measures measure(const Eigen::Vector3d& p0, const FarEdge& e, const StretchTarget& t) {
  Measures m;
  const double m0 = e.length2;
  m.to_b2 = (e.b - p0).squaredNorm();
  m.to_a2 = (p0 - e.a).squaredNorm();
  const double m1 = m.to_b2, m2 = m.to_a2;
  const double sum_l = t.l[0] + t.l[1] + t.l[2];
  m.N = 0.5 * (sum_l * (m0 + m1 + m2) - 2 * (t.l[0] * m0 + t.l[1] * m1 + t.l[2] * m2));
  // D = 4·(spherical area)², by Van Oosterom and Strackee's formula, rather than the chord
  // triangle's |(p1 − p0) × (p2 − p0)|²: the two agree for small triangles, but only the spherical
  // area vanishes when a large triangle degenerates (its corners on one great circle) and stays
  // right at the scale of a tetrahedron's faces.
  m.volume = p0.dot(e.a_cross_b);
  m.w = 1 + p0.dot(e.a) + e.a_dot_b + e.b.dot(p0);
  m.area = 2 * angle_of(m.volume, m.w);
  m.D = 4 * m.area * m.area;
  return m;
}

// The sign of det(p0, a, b), exact: the measured volume's rounding is below 6u times the
// permanent Σ|p0_i|(|a_j b_k| + |a_k b_j|) (u = 2^-53), so beyond 32u times it the volume's sign
// is the determinant's; nearer zero, exact arithmetic decides.
int orientation_of(const Eigen::Vector3d& p0, const FarEdge& e, double volume) {
  const double permanent =
      std::abs(p0[0]) * e.cross_bound[0] + std::abs(p0[1]) * e.cross_bound[1] + std::abs(p0[2]) * e.cross_bound[2];
  const double bound = 16 * std::numeric_limits<double>::epsilon() * permanent;
  if (volume > bound) return 1;
  if (volume < -bound) return -1;
  return orientation_sign(p0, e.a, e.b);
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

// E = m² · √2/2 · N^¼ · D^(−5/8), by square roots. √D is 2·area exactly: D = 4·area², and in
// binary floating point the square root of a rounded square rounds back to its root (the factor 4
// is exact) unless the square underflows. That takes one square root off the chain the line
// search waits on, and changes no bit.
double energy_of(const Measures& m, double mass) {
  const double root_d = m.area > 1e-150 ? 2 * m.area : std::sqrt(m.D);
  const double eighth_d = std::sqrt(std::sqrt(root_d));
  return 0.5 * std::sqrt(2.0) * mass * mass * std::sqrt(std::sqrt(m.N)) / (root_d * eighth_d);
}

namespace {

double energy_at(const Measures& m, double mass) {
  if (!(m.area > 0) || !(m.N > 0)) return kInfinity;
  return energy_of(m, mass);
}

// E and its gradient with respect to p0, from the face's measures at p0.
double energy_gradient_at(const Measures& m, const Eigen::Vector3d& p0, const FarEdge& e, const StretchTarget& t,
                          Eigen::Vector3d& gradient) {
  if (!(m.area > 0)) {
    gradient.setZero();
    return kInfinity;
  }
  // ∇N = (l0 + l2 − l1)(p0 − p2) + (l0 + l1 − l2)(p0 − p1);  ∇D = 8A ∇A, with
  // ∇A = 2 (w ∇det − det ∇w) / (det² + w²), ∇det = p1 × p2, ∇w = p1 + p2.
  const Eigen::Vector3d dN = (t.l[0] + t.l[2] - t.l[1]) * (p0 - e.b) + (t.l[0] + t.l[1] - t.l[2]) * (p0 - e.a);
  const Eigen::Vector3d dA = 2 * (m.w * e.a_cross_b - m.volume * (e.a + e.b)) / (m.volume * m.volume + m.w * m.w);
  const Eigen::Vector3d dD = 8 * m.area * dA;
  if (!(m.N > 0)) {
    gradient.setZero();
    return kInfinity;
  }
  const double E = energy_of(m, t.mass);
  gradient = E * (0.25 * dN / m.N - 0.625 * dD / m.D);
  return E;
}

}  // namespace

double stretch_energy(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                      const StretchTarget& t) {
  return energy_at(measure(p0, FarEdge(p1, p2), t), t.mass);
}

double stretch_energy_gradient(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                               const StretchTarget& t, Eigen::Vector3d& gradient) {
  const FarEdge e(p1, p2);
  return energy_gradient_at(measure(p0, e, t), p0, e, t, gradient);
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

// A star's faces with their far edges gathered once: the line search evaluates them several
// times, and fetching rows of S by index each time was most of its cost.
struct LocalStar {
  std::vector<FarEdge> edges;
  std::vector<StretchTarget> targets;

  template <typename Star>
  void gather(const Vertices& S, const Star& star) {
    const std::size_t k = star.size();
    edges.resize(k);
    targets.resize(k);
    for (std::size_t i = 0; i < k; ++i) {
      const auto o = star.others(i);
      edges[i] = FarEdge(S.row(o[0]).transpose(), S.row(o[1]).transpose());
      targets[i] = star.target(i);
    }
  }
  std::size_t size() const { return edges.size(); }
};

// The star's energy and gradient along the sphere at x; +∞ when a face is so thin that doubles
// cannot tell its gradient (sin of its smallest angle below ~1e-10): the caller then steps
// towards the star's centre, which any finite energy improves on.
double star_energy_gradient(const LocalStar& star, const Eigen::Vector3d& x, Eigen::Vector3d& g) {
  double energy = 0;
  g.setZero();
  for (std::size_t i = 0; i < star.size(); ++i) {
    const FarEdge& e = star.edges[i];
    const Measures m = measure(x, e, star.targets[i]);
    const double scale = std::max({m.to_a2, m.to_b2, e.length2});
    if (!(m.volume * m.volume > 1e-20 * scale * scale)) return std::numeric_limits<double>::infinity();
    Eigen::Vector3d gi;
    energy += energy_gradient_at(m, x, e, star.targets[i], gi);
    g += gi;
  }
  g -= g.dot(x) * x;
  return energy;
}

// The energy at x if every face stays positively oriented (decided exactly) and the energy is
// below `bound`, else nullopt. Energies are never negative, so a partial sum that reaches the
// bound decides.
std::optional<double> star_energy_below(const LocalStar& star, const Eigen::Vector3d& x, double bound) {
  double energy = 0;
  for (std::size_t i = 0; i < star.size(); ++i) {
    const FarEdge& e = star.edges[i];
    const Measures m = measure(x, e, star.targets[i]);
    if (orientation_of(x, e, m.volume) <= 0) return std::nullopt;
    energy += energy_at(m, star.targets[i].mass);
    if (!(energy < bound)) return std::nullopt;
  }
  return energy;
}

// One descent step of v over its gathered star (see improve_vertex).
bool step_down(Vertices& S, int v, const LocalStar& star, double& step, const StretchDescentOptions& options) {
  const std::size_t k = star.size();
  if (k == 0) return false;
  const Eigen::Vector3d p = S.row(v).transpose();
  double edge_sum = 0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < k; ++i) {
    centre += star.edges[i].a;
    edge_sum += (star.edges[i].a - p).norm();
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
  // A colour's vertices are independent, so their order changes no result; in index order they
  // walk S and the stars through memory instead of in the insertion order's random jumps.
  for (std::vector<int>& group : colours) std::sort(group.begin(), group.end());
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
