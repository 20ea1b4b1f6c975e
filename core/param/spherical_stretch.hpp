#pragma once
// The energy that spreads a spherical map's area fairly (after Praun and Hoppe 2003, who minimize
// the L2 stretch of the map), and a fold-free descent on it.
//
// A face's target is a triangle of unit area, given by its squared edge lengths l_i (l_i opposite
// corner i), and a mass m. Its image (p0, p1, p2) on the unit sphere, of area A, costs
//
//     E = ½ m²/A · S^¼,   S = A · ½ tr(G_p⁻¹ G_t) ≥ 1,
//
// where S measures how far the image's shape is from the target's (1: the same). We compute it as
// E = (√2/2) m² N^¼ D^(−5/8) with N = ½ [(Σ l_i)(Σ m_i) − 2 Σ l_i m_i] (m_i the squared chord
// lengths) and D = 4A², A the spherical area (for a small triangle the chord triangle's area, but
// also right for large ones, and 0 when the spherical triangle degenerates, where the chord
// triangle would not). Under a fixed total area, Σ m²/A is
// smallest when every face's area is proportional to its mass: compressed protrusions cost the
// most, and a degenerate image costs without bound. The shape enters with the power ¼: with the
// power 1 this is Praun and Hoppe's (2003) area-weighted L2 stretch, which on limbs and blades
// trades area for shape (5 % of the sword's faces kept under 3 % of their share); with ¼ area
// comes first and the triangles still keep their shape (measured on the corpus). N and D do not
// depend on which corner comes first, so a vertex's faces can be evaluated with it first.

#include <array>
#include <functional>
#include <vector>

#include "core/mesh/mesh.hpp"
#include "core/mesh/vertex_faces.hpp"
#include "core/util/job_control.hpp"

namespace meshmark {

struct StretchTarget {
  double mass = 0;
  std::array<double, 3> l{};  ///< squared edge lengths of the unit-area target, l[i] opposite corner i

  /// The same target with corner `first` of the face put first.
  StretchTarget rotated(int first) const { return {mass, {l[first], l[(first + 1) % 3], l[(first + 2) % 3]}}; }
};

/// An equilateral target of the given mass (for coarse levels, whose faces stand for many).
StretchTarget equilateral_target(double mass);
/// The face (q0, q1, q2) itself: its area as mass, its shape; a degenerate face gets an
/// equilateral shape.
StretchTarget face_target(const Eigen::Vector3d& q0, const Eigen::Vector3d& q1, const Eigen::Vector3d& q2);

/// E of the chord triangle (p0, p1, p2) with target t (in that corner order); +∞ when it is
/// degenerate in floating point.
double stretch_energy(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                      const StretchTarget& t);
/// E and its gradient with respect to p0.
double stretch_energy_gradient(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                               const StretchTarget& t, Eigen::Vector3d& gradient);

/// A vertex's faces, each as (vertex, a, b) wound outward, with its target rotated to match.
struct VertexStar {
  std::vector<std::array<int, 2>> others;
  std::vector<StretchTarget> targets;
  void clear() {
    others.clear();
    targets.clear();
  }
};

struct StretchDescentOptions {
  int sweeps = 10;           ///< passes over the vertices
  int max_halvings = 6;      ///< a refused step is halved at most this often per vertex and pass
  double first_step = 0.25;  ///< a vertex's first step, in units of its mean edge length
  double max_step = 0.2;     ///< radians: every step is far below π, so no face can flip and back
};

/// Up to `steps` descent steps of vertex v alone over its star, whose other vertices stay put.
/// Each goes along the negative gradient on the sphere (or, where a face is degenerate in
/// floating point, towards the star's centre), halving the step until the star's energy falls
/// and every face stays positively oriented (decided exactly); the first that finds no such step
/// ends the run. Returns the steps taken.
int improve_vertex(Vertices& S, int v, const VertexStar& star, int steps, const StretchDescentOptions& options);

struct StretchDescentResult {
  long long moves = 0;    ///< steps taken
  long long refused = 0;  ///< vertices that found no improving fold-free step in a pass
};

/// A level of the map, ready for descent: each movable vertex's faces, and a colouring of the
/// movable vertices in which no two neighbours share a colour (so a colour's vertices move at
/// once, on any number of threads, with the same result).
struct StretchProblem {
  /// One face of a vertex's star: its other corners, wound outward after the vertex, and its
  /// target rotated to start at the vertex. Kept whole per star, so that a descent step reads
  /// its star from one place (by face index, the reads jumped across the mesh).
  struct StarFace {
    std::array<int, 2> others;
    StretchTarget target;
  };
  /// `targets`: one per face of F.
  StretchProblem(const Faces& F, const std::vector<StretchTarget>& targets, Eigen::Index vertex_count,
                 const std::vector<int>& movable);
  std::vector<int> star_offsets;          ///< per vertex (#V + 1)
  std::vector<StarFace> star;             ///< each vertex's faces, in the order of F
  std::vector<std::vector<int>> colours;  ///< the movable vertices, by colour, each in index order
};

/// Moves vertex v towards the centroid of its neighbours (a spherical Tutte step), as far as
/// every face of its star stays positively oriented (exact test), trying the whole way, then
/// half, a quarter...: fattens the thin wedges a stretch descent may leave. True if it moved.
bool step_towards_neighbours(Vertices& S, int v, const StretchProblem& problem);

/// Gauss–Seidel descent of Σ E over a level, colour by colour: a fold-free map stays fold-free.
/// `step` holds each vertex's step length between calls (0: not yet known). Deterministic
/// whatever the number of threads. Polls `control`; `progress` (if given) hears after each colour
/// the fraction of the passes done.
StretchDescentResult descend_stretch(Vertices& S, const StretchProblem& problem, std::vector<double>& step,
                                     const StretchDescentOptions& options, const JobControl* control = nullptr,
                                     const std::function<void(double)>& progress = {});

}  // namespace meshmark
