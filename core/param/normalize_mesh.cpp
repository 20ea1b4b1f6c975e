#include "core/param/normalize_mesh.hpp"

#include <cmath>

#include "core/mesh/massmatrix.hpp"

namespace meshmark {

Normalization unit_area_normalization(const Vertices& V, const Faces& F) {
  const Eigen::VectorXd area = face_areas(V, F);
  Normalization n;
  Eigen::RowVector3d weighted = Eigen::RowVector3d::Zero();
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    weighted += area[f] * (V.row(F(f, 0)) + V.row(F(f, 1)) + V.row(F(f, 2))) / 3.0;
  const double total = area.sum();
  n.center = weighted / total;
  n.scale = 1.0 / std::sqrt(total);
  return n;
}

Vertices apply(const Normalization& n, const Vertices& V) { return ((V.rowwise() - n.center) * n.scale).eval(); }

}  // namespace meshmark
