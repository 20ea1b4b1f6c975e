#include "core/param/equalize_area.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <algorithm>
#include <cmath>

#include "core/mesh/edge_incidence.hpp"
#include "core/mesh/vertex_faces.hpp"
#include "core/param/cotmatrix.hpp"
#include "core/param/exact_orientation.hpp"
#include "core/mesh/massmatrix.hpp"
#include "core/util/parallel_for.hpp"
#include "core/wavelet/spherical_wavelet.hpp"

namespace meshmark {

namespace {

// The coarse grid the density lives on, with what diffusion, gradients and point location need.
struct DensityGrid {
  SphereGrid grid;
  int level = 0;
  Faces F;
  std::vector<std::array<int, 3>> across;  // the face across edge k (from corner k to k+1)
  Eigen::SparseMatrix<double> L;           // cotangent stiffness of the flat grid
  Eigen::VectorXd M;                       // its lumped mass
  Eigen::VectorXd share;                   // each grid point's share of the sphere (sums to 1)
  double spacing = 0;                      // typical edge length

  explicit DensityGrid(int grid_level)
      : grid(make_sphere_grid(BaseSolid::icosahedron, grid_level)), level(grid_level), F(grid.faces[grid_level]) {
    L = cotmatrix(grid.points, F);
    M = vertex_areas(grid.points, F);
    share = finest_integrals(grid, level) / (4 * M_PI);
    spacing = 1.1 / std::ldexp(1.0, level);
    const EdgeIncidence inc = edge_incidence(F);
    std::vector<std::array<int, 2>> faces_of_edge(inc.face_count.size(), {-1, -1});
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      for (int k = 0; k < 3; ++k)
        faces_of_edge[inc.face_edges(f, k)][F(f, k) < F(f, (k + 1) % 3) ? 0 : 1] = static_cast<int>(f);
    across.resize(static_cast<std::size_t>(F.rows()));
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      for (int k = 0; k < 3; ++k) {
        const auto& pair = faces_of_edge[inc.face_edges(f, k)];
        across[f][k] = pair[0] == f ? pair[1] : pair[0];
      }
  }

  const Vertices& P() const { return grid.points; }

  // ρ ← (M + dt L)⁻¹ M ρ by conjugate gradients, warm-started at ρ: cheaper than a factorization
  // per step size, and the early, tiny steps converge in a few iterations.
  void diffuse(Eigen::VectorXd& rho, double dt) const {
    Eigen::SparseMatrix<double> A = dt * L;
    A.diagonal() += M;
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg(A);
    cg.setTolerance(1e-7);
    const Eigen::VectorXd rhs = M.cwiseProduct(rho);
    rho = cg.solveWithGuess(rhs, rho).eval();
  }

  // Where p lies, starting from the face it was in: stay, step across an edge, or descend.
  GridLocation relocate(int face, const Eigen::Vector3d& p) const {
    for (int hop = 0; hop < 2; ++hop) {
      const Eigen::Vector3d a = P().row(F(face, 0)), b = P().row(F(face, 1)), c = P().row(F(face, 2));
      const double m[3] = {a.cross(b).dot(p), b.cross(c).dot(p), c.cross(a).dot(p)};
      const int worst = static_cast<int>(std::min_element(m, m + 3) - m);
      if (m[worst] >= 0) return {face, gnomonic_barycentric(p, a, b, c)};
      face = across[face][worst];
    }
    return locate_in_grid(grid, p, level);
  }
};

int pick_level(const EqualizeAreaOptions& options, Eigen::Index vertices) {
  int level = 2;
  while (level < 5 && static_cast<double>(sphere_grid_vertex_count(BaseSolid::icosahedron, level + 1)) *
                              options.vertices_per_grid_point <=
                          static_cast<double>(vertices))
    ++level;
  return level;
}

// ρ on the grid: each triangle's share of the surface spread over the part of the sphere it
// covers (split into k² pieces no wider than half a grid cell), divided by each grid point's
// share of the sphere. A large triangle thus reaches every grid point under it.
Eigen::VectorXd deposit(const DensityGrid& g, const Vertices& S, const Faces& F, const Eigen::VectorXd& face_mass) {
  Eigen::VectorXd rho = Eigen::VectorXd::Zero(g.P().rows());
  GridLocation cell = locate_in_grid(g.grid, S.row(0), g.level);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = S.row(F(f, 0)), b = S.row(F(f, 1)), c = S.row(F(f, 2));
    const double longest = std::max({(a - b).norm(), (b - c).norm(), (c - a).norm()});
    const int k = std::max(1, static_cast<int>(std::ceil(2 * longest / g.spacing)));
    const double piece = face_mass[f] / (k * k);
    for (int i = 0; i < k; ++i)  // the k² sub-triangles of a k-fold split, by their centroids
      for (int j = 0; i + j < k; ++j)
        for (int up = 0; up < (i + j + 1 < k ? 2 : 1); ++up) {
          const double u = (i + (up ? 2.0 : 1.0) / 3) / k, v = (j + (up ? 2.0 : 1.0) / 3) / k;
          cell = g.relocate(cell.face, ((1 - u - v) * a + u * b + v * c).normalized());
          for (int q = 0; q < 3; ++q) rho[g.F(cell.face, q)] += piece * cell.bary[q];
        }
  }
  return rho.cwiseQuotient(g.share);
}

// Velocity −∇ρ/ρ at the grid points (tangent to the sphere), and the largest velocity
// gradient along any grid edge.
Vertices velocity(const DensityGrid& g, const Eigen::VectorXd& rho, double& max_gradient) {
  const Vertices& P = g.P();
  Vertices grad = Vertices::Zero(P.rows(), 3);
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(P.rows());
  for (Eigen::Index f = 0; f < g.F.rows(); ++f) {
    const int i = g.F(f, 0), j = g.F(f, 1), k = g.F(f, 2);
    const Eigen::Vector3d a = P.row(i), b = P.row(j), c = P.row(k);
    const Eigen::Vector3d n2 = (b - a).cross(c - a);
    const double area2 = n2.norm();
    const Eigen::Vector3d n = n2 / area2;
    const Eigen::Vector3d gf = (rho[i] * n.cross(c - b) + rho[j] * n.cross(a - c) + rho[k] * n.cross(b - a)) / area2;
    for (int v : {i, j, k}) {
      grad.row(v) += area2 * gf.transpose();
      weight[v] += area2;
    }
  }
  Vertices v(P.rows(), 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const Eigen::Vector3d p = P.row(i), gi = grad.row(i).transpose() / weight[i];
    v.row(i) = (-(gi - gi.dot(p) * p) / rho[i]).transpose();
  }
  max_gradient = 0;
  for (Eigen::Index f = 0; f < g.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = g.F(f, k), b = g.F(f, (k + 1) % 3);
      max_gradient = std::max(max_gradient, (v.row(a) - v.row(b)).norm() / (P.row(a) - P.row(b)).norm());
    }
  return v;
}

bool folded(const Vertices& S, const Faces& F, Eigen::Index f) {
  return orientation_sign(S.row(F(f, 0)), S.row(F(f, 1)), S.row(F(f, 2))) <= 0;
}

// One pass of the flow on one density grid.
void equalize_on_grid(Vertices& S, const Faces& F, const VertexFaces& vf, const Eigen::VectorXd& face_mass,
                      const EqualizeAreaOptions& options, const DensityGrid& g, EqualizeAreaResult& result,
                      const JobControl* control) {
  std::vector<GridLocation> cells(static_cast<std::size_t>(S.rows()));
  parallel_for(S.rows(), threads_of(control), [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i) cells[i] = locate_in_grid(g.grid, S.row(i), g.level);
  });
  Eigen::VectorXd rho = deposit(g, S, F, face_mass / face_mass.sum());
  result.spread_before = std::max(result.spread_before, (rho.array() - 1).abs().maxCoeff());
  // Blur the deposit over about a grid cell, so that a cell few triangles cover does not read as empty.
  g.diffuse(rho, 0.25 * g.spacing * g.spacing);

  double strain = options.max_strain, time = 0;
  Vertices moved(S.rows(), 3);
  std::vector<GridLocation> moved_cells(cells.size());
  std::vector<int> to_check;
  std::vector<char> is_folded(static_cast<std::size_t>(F.rows()));
  for (int step = 0; step < options.max_steps && time < options.max_time; ++step) {
    poll(control);
    if ((rho.array() - 1).abs().maxCoeff() < options.tolerance) break;
    ++result.steps;
    double max_gradient = 0;
    const Vertices v = velocity(g, rho, max_gradient);
    const double dt = strain / std::max(max_gradient, 1e-300);
    parallel_for(S.rows(), threads_of(control), [&](std::int64_t begin, std::int64_t end) {
      for (std::int64_t i = begin; i < end; ++i) {
        const GridLocation& c = cells[i];
        const Eigen::Vector3d vi =
            c.bary[0] * v.row(g.F(c.face, 0)) + c.bary[1] * v.row(g.F(c.face, 1)) + c.bary[2] * v.row(g.F(c.face, 2));
        moved.row(i) = (S.row(i).transpose() + dt * vi).normalized().transpose();
        moved_cells[i] = g.relocate(c.face, moved.row(i));
      }
    });
    // A triangle the flow would fold (typically one larger than a grid cell, squeezed across it)
    // keeps its corners still for this step; only the faces around them need checking again.
    parallel_for(F.rows(), threads_of(control), [&](std::int64_t begin, std::int64_t end) {
      for (std::int64_t f = begin; f < end; ++f) is_folded[f] = folded(moved, F, f);
    });
    to_check.clear();
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      if (is_folded[f]) to_check.push_back(static_cast<int>(f));
    for (int round = 0; round < options.freeze_rounds && !to_check.empty(); ++round) {
      ++result.rejected_steps;
      std::vector<int> around;
      for (int f : to_check)
        for (int k = 0; k < 3; ++k) {
          const int i = F(f, k);
          if (moved.row(i) == S.row(i)) continue;
          moved.row(i) = S.row(i);
          moved_cells[i] = cells[i];
          around.insert(around.end(), vf.faces.begin() + vf.offsets[i], vf.faces.begin() + vf.offsets[i + 1]);
        }
      to_check.clear();
      std::sort(around.begin(), around.end());
      around.erase(std::unique(around.begin(), around.end()), around.end());
      for (int f : around)
        if (folded(moved, F, f)) to_check.push_back(f);
    }
    if (!to_check.empty()) {  // freezing did not settle it: retry the step smaller, give up eventually
      strain *= 0.5;
      if (strain < options.max_strain / 64) break;
      continue;
    }
    S.swap(moved);
    cells.swap(moved_cells);
    g.diffuse(rho, dt);
    time += dt;
    strain = std::min(options.max_strain, strain * 1.25);
  }
  result.time += time;
  result.spread_after = (rho.array() - 1).abs().maxCoeff();
}

}  // namespace

EqualizeAreaResult equalize_area(Vertices& S, const Faces& F, const Eigen::VectorXd& face_mass,
                                 const EqualizeAreaOptions& options, const JobControl* control) {
  EqualizeAreaResult result;
  std::vector<int> levels = options.grid_levels;
  if (levels.empty()) {
    const int coarse = pick_level(options, S.rows());
    levels = {coarse, coarse + 1};
  }
  const VertexFaces vf = vertex_faces(F, S.rows());
  for (int level : levels) {
    const DensityGrid grid(level);
    equalize_on_grid(S, F, vf, face_mass, options, grid, result, control);
    result.grid_levels.push_back(level);
  }
  return result;
}

}  // namespace meshmark
