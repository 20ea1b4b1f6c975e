#pragma once
// One face's stretch energy (core/param/spherical_stretch.hpp) and its gradient, written once for
// a lane type T: double (one face) or Eigen::Array2d (two faces of a star at once, on the SIMD
// unit). Every lane performs the same IEEE operations in the same order as the double version,
// so the two give the same bits (no multiply-add is fused: -ffp-contract=off, CMakeLists.txt);
// the descent waits on each face's chain of divisions and square roots, and two faces per
// instruction halve the chains it waits on.

#include <Eigen/Core>
#include <cmath>
#include <limits>

namespace meshmark::stretch_face {

using Pair = Eigen::Array2d;
using PairMask = Eigen::Array<bool, 2, 1>;

// What a lane type's comparisons give, and a value in every lane.
template <typename T>
struct Lanes;
template <>
struct Lanes<double> {
  using Mask = bool;
  static double fill(double value) { return value; }
};
template <>
struct Lanes<Pair> {
  using Mask = PairMask;
  static Pair fill(double value) { return Pair::Constant(value); }
};

inline bool all(bool condition) { return condition; }
inline bool all(const PairMask& condition) { return condition.all(); }
inline double pick(bool condition, double yes, double no) { return condition ? yes : no; }
inline Pair pick(const PairMask& condition, const Pair& yes, const Pair& no) { return condition.select(yes, no); }

constexpr double kInfinity = std::numeric_limits<double>::infinity();

template <typename T>
struct Point {
  T x, y, z;
};

template <typename T>
[[gnu::always_inline]] inline T dot(const Point<T>& p, const Point<T>& q) {
  return p.x * q.x + p.y * q.y + p.z * q.z;
}

template <typename T>
[[gnu::always_inline]] inline T squared_distance(const Point<T>& p, const Point<T>& q) {
  const T dx = p.x - q.x, dy = p.y - q.y, dz = p.z - q.z;
  return dx * dx + dy * dy + dz * dz;
}

template <typename T>
struct Target {
  T mass, l0, l1, l2;  // l_i: the squared edge length opposite corner i
};

// A face's edge opposite the moving corner, with what does not depend on that corner: the line
// search evaluates a star's faces several times at new positions of the one vertex.
template <typename T>
struct FarEdge {
  Point<T> a, b, a_cross_b;
  T a_dot_b, length2;    // a·b, |a − b|²
  Point<T> cross_bound;  // |a_j b_k| + |a_k b_j|: bounds the rounding of a × b
};

template <typename T>
[[gnu::always_inline]] inline FarEdge<T> far_edge(const Point<T>& a, const Point<T>& b) {
  using std::abs;
  return {a,
          b,
          {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x},
          dot(a, b),
          squared_distance(a, b),
          {abs(a.y * b.z) + abs(a.z * b.y), abs(a.z * b.x) + abs(a.x * b.z), abs(a.x * b.y) + abs(a.y * b.x)}};
}

template <typename T>
struct Measures {
  T N, D;
  T volume, w, area;  // det(p0, p1, p2); 1 + Σ pi·pj; the spherical area
  T to_b2, to_a2;     // |p2 − p0|², |p0 − p1|²
};

// atan(t) by its series, for |t| < 0.1 (the error is below 1e-10 of the value).
template <typename T>
[[gnu::always_inline]] inline T small_arctangent(const T& t) {
  const T t2 = t * t;
  return t * (1 - t2 * (1.0 / 3 - t2 * (1.0 / 5 - t2 * (1.0 / 7))));
}

// atan2(y, x), by the series where x > 0 and |y/x| < 0.1 (the faces of any fine mesh), where
// atan2 itself was a fifth of the descent's time.
inline double angle_of(double y, double x) {
  if (x > 0) {
    const double t = y / x;
    if (std::abs(t) < 0.1) return small_arctangent(t);
  }
  return std::atan2(y, x);
}

[[gnu::always_inline]] inline Pair angle_of(const Pair& y, const Pair& x) {
  const Pair t = y / x;
  Pair series = small_arctangent(t);
  const PairMask small = (x > 0) && (t.abs() < 0.1);
  if (small.all()) return series;
  return {small[0] ? series[0] : std::atan2(y[0], x[0]), small[1] ? series[1] : std::atan2(y[1], x[1])};
}

template <typename T>
[[gnu::always_inline]] inline Measures<T> measure(const Point<T>& p0, const FarEdge<T>& e, const Target<T>& t) {
  Measures<T> m;
  const T m0 = e.length2;
  m.to_b2 = squared_distance(e.b, p0);
  m.to_a2 = squared_distance(p0, e.a);
  const T sum_l = t.l0 + t.l1 + t.l2;
  m.N = 0.5 * (sum_l * (m0 + m.to_b2 + m.to_a2) - 2 * (t.l0 * m0 + t.l1 * m.to_b2 + t.l2 * m.to_a2));
  // D = 4·(spherical area)², by Van Oosterom and Strackee's formula, rather than the chord
  // triangle's |(p1 − p0) × (p2 − p0)|²: the two agree for small triangles, but only the spherical
  // area vanishes when a large triangle degenerates (its corners on one great circle) and stays
  // right at the scale of a tetrahedron's faces.
  m.volume = dot(p0, e.a_cross_b);
  m.w = 1 + dot(p0, e.a) + e.a_dot_b + dot(e.b, p0);
  m.area = 2 * angle_of(m.volume, m.w);
  m.D = 4 * m.area * m.area;
  return m;
}

// Beyond this the measured volume's sign is det(p0, a, b)'s: its rounding is below 6u times the
// permanent Σ|p0_i|(|a_j b_k| + |a_k b_j|) (u = 2^-53); nearer zero, exact arithmetic decides.
template <typename T>
[[gnu::always_inline]] inline T volume_sign_bound(const Point<T>& p0, const FarEdge<T>& e) {
  using std::abs;
  const T permanent = abs(p0.x) * e.cross_bound.x + abs(p0.y) * e.cross_bound.y + abs(p0.z) * e.cross_bound.z;
  return 16 * std::numeric_limits<double>::epsilon() * permanent;
}

// E = m² · √2/2 · N^¼ · D^(−5/8), by square roots. √D is 2·area exactly: D = 4·area², and in
// binary floating point the square root of a rounded square rounds back to its root (the factor 4
// is exact) unless the square underflows.
template <typename T>
[[gnu::always_inline]] inline T energy_of(const Measures<T>& m, const T& mass) {
  using std::sqrt;
  T root_d = 2 * m.area;
  const typename Lanes<T>::Mask normal = m.area > 1e-150;
  if (!all(normal)) root_d = pick(normal, root_d, T(sqrt(m.D)));  // rare: skip its square root
  const T eighth_d = sqrt(sqrt(root_d));
  return 0.5 * std::sqrt(2.0) * mass * mass * sqrt(sqrt(m.N)) / (root_d * eighth_d);
}

// E, or +∞ where the image is degenerate.
template <typename T>
[[gnu::always_inline]] inline T energy_at(const Measures<T>& m, const T& mass) {
  const typename Lanes<T>::Mask valid = m.area > 0 && m.N > 0;
  return pick(valid, energy_of(m, mass), Lanes<T>::fill(kInfinity));
}

// E and its gradient with respect to p0, from the face's measures at p0 (+∞ and 0 where the
// image is degenerate).
template <typename T>
[[gnu::always_inline]] inline T energy_gradient_at(const Measures<T>& m, const Point<T>& p0, const FarEdge<T>& e,
                                                   const Target<T>& t, Point<T>& gradient) {
  // ∇N = (l0 + l2 − l1)(p0 − p2) + (l0 + l1 − l2)(p0 − p1);  ∇D = 8A ∇A, with
  // ∇A = 2 (w ∇det − det ∇w) / (det² + w²), ∇det = p1 × p2, ∇w = p1 + p2.
  const T to_b = t.l0 + t.l2 - t.l1, to_a = t.l0 + t.l1 - t.l2;
  const T denominator = m.volume * m.volume + m.w * m.w;
  const T area8 = 8 * m.area;
  const T E = energy_of(m, t.mass);
  const auto coordinate = [&](const T& p, const T& a, const T& b, const T& a_cross_b) -> T {
    const T dN = to_b * (p - b) + to_a * (p - a);
    const T dA = 2 * (m.w * a_cross_b - m.volume * (a + b)) / denominator;
    const T dD = area8 * dA;
    return E * (0.25 * dN / m.N - 0.625 * dD / m.D);
  };
  const typename Lanes<T>::Mask valid = m.area > 0 && m.N > 0;
  const T zero = Lanes<T>::fill(0);
  gradient.x = pick(valid, coordinate(p0.x, e.a.x, e.b.x, e.a_cross_b.x), zero);
  gradient.y = pick(valid, coordinate(p0.y, e.a.y, e.b.y, e.a_cross_b.y), zero);
  gradient.z = pick(valid, coordinate(p0.z, e.a.z, e.b.z, e.a_cross_b.z), zero);
  return pick(valid, E, Lanes<T>::fill(kInfinity));
}

}  // namespace meshmark::stretch_face
