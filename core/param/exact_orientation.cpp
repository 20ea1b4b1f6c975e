#include "core/param/exact_orientation.hpp"

#include <cmath>
#include <limits>

namespace meshmark {

namespace {

// x + y = s + e exactly (Knuth's two-sum).
inline void two_sum(double x, double y, double& s, double& e) {
  s = x + y;
  const double bv = s - x;
  e = (x - (s - bv)) + (y - bv);
}

// x · y = p + e exactly, with a fused multiply-add.
inline void two_product(double x, double y, double& p, double& e) {
  p = x * y;
  e = std::fma(x, y, -p);
}

// A sum of doubles kept exactly as a non-overlapping expansion (components ascending in
// magnitude); adding a double keeps it exact.
class Expansion {
 public:
  void add(double b) {
    int out = 0;
    double q = b;
    for (int i = 0; i < size_; ++i) {
      double s, e;
      two_sum(q, c_[i], s, e);
      q = s;
      if (e != 0) c_[out++] = e;
    }
    if (q != 0) c_[out++] = q;
    size_ = out;
  }
  int sign() const { return size_ == 0 ? 0 : (c_[size_ - 1] > 0 ? 1 : -1); }

 private:
  double c_[32] = {};  // 6 terms × 4 parts bound the length by 24
  int size_ = 0;
};

// Adds sign · x · y · z to `sum` exactly: four doubles.
void add_triple_product(Expansion& sum, double sign, double x, double y, double z) {
  double p, pe;
  two_product(sign * x, y, p, pe);
  double q, qe, r, re;
  two_product(p, z, q, qe);
  two_product(pe, z, r, re);
  sum.add(re);
  sum.add(qe);
  sum.add(r);
  sum.add(q);
}

}  // namespace

int orientation_sign(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double t[6] = {a.x() * b.y() * c.z(), a.y() * b.z() * c.x(), a.z() * b.x() * c.y(),
                       a.z() * b.y() * c.x(), a.x() * b.z() * c.y(), a.y() * b.x() * c.z()};
  const double det = (t[0] + t[1] + t[2]) - (t[3] + t[4] + t[5]);
  double permanent = 0;
  for (double v : t) permanent += std::abs(v);
  // Each product has relative error ≤ 2u and the five additions add ≤ 3u of the permanent;
  // 8u is a safe bound (u = 2^-53), doubled again for the rounding of the bound itself.
  const double bound = 16 * std::numeric_limits<double>::epsilon() * permanent;
  if (det > bound) return 1;
  if (det < -bound) return -1;
  if (permanent == 0) return 0;

  Expansion sum;
  add_triple_product(sum, 1, a.x(), b.y(), c.z());
  add_triple_product(sum, 1, a.y(), b.z(), c.x());
  add_triple_product(sum, 1, a.z(), b.x(), c.y());
  add_triple_product(sum, -1, a.z(), b.y(), c.x());
  add_triple_product(sum, -1, a.x(), b.z(), c.y());
  add_triple_product(sum, -1, a.y(), b.x(), c.z());
  return sum.sign();
}

}  // namespace meshmark
