#include "core/param/progressive_sphere_map.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <mutex>
#include <stdexcept>

#include "core/mesh/vertex_faces.hpp"
#include "core/param/check_spherical_map.hpp"
#include "core/param/exact_orientation.hpp"
#include "core/mesh/massmatrix.hpp"
#include "core/param/progressive_mesh.hpp"
#include "core/param/sphere_param.hpp"
#include "core/util/parallel_for.hpp"

namespace meshmark {

namespace {

using Clock = std::chrono::steady_clock;

// Insertions per thread at least (one takes a few microseconds, starting a thread tens), and
// per slice a thread takes at a time.
constexpr std::int64_t kWaveGrain = 256, kWaveSlice = 64;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The refinement's state: which vertices are in, where they are, and how to rebuild any level.
class Refinement {
 public:
  Refinement(const Vertices& V, const Faces& F, const ProgressiveMesh& pm)
      : V_(V), F_(F), pm_(pm), order_(insertion_order(pm)), n_(V.rows()) {
    parent_.assign(static_cast<std::size_t>(n_), -1);
    collapse_of_.assign(static_cast<std::size_t>(n_), -1);
    for (std::size_t i = 0; i < pm.collapses(); ++i) {
      parent_[static_cast<std::size_t>(pm.removed[i])] = pm.kept[i];
      collapse_of_[static_cast<std::size_t>(pm.removed[i])] = static_cast<int>(i);
    }
    vertex_area_ = vertex_areas(V, F);
    S_ = Vertices::Zero(n_, 3);
    step_.assign(static_cast<std::size_t>(n_), 0.0);
    place_base();
  }

  Eigen::Index size() const { return n_; }
  const std::vector<int>& order() const { return order_; }
  Vertices& positions() { return S_; }
  std::vector<double>& steps() { return step_; }

  // The representative of every vertex when the first `active` of the insertion order are in.
  std::vector<int> representatives(Eigen::Index active) const {
    std::vector<int> rep(static_cast<std::size_t>(n_));
    for (Eigen::Index j = 0; j < n_; ++j) {
      const auto v = static_cast<std::size_t>(order_[static_cast<std::size_t>(j)]);
      rep[v] = j < active ? static_cast<int>(v) : rep[static_cast<std::size_t>(parent_[v])];
    }
    return rep;
  }

  // The faces of the mesh with the first `active` vertices in: the input's, each corner replaced
  // by its representative, without those that collapsed.
  Faces level_faces(Eigen::Index active) const {
    const std::vector<int> rep = representatives(active);
    std::vector<int> kept;
    kept.reserve(static_cast<std::size_t>(3 * F_.rows()));
    for (Eigen::Index f = 0; f < F_.rows(); ++f) {
      const int a = rep[static_cast<std::size_t>(F_(f, 0))], b = rep[static_cast<std::size_t>(F_(f, 1))],
                c = rep[static_cast<std::size_t>(F_(f, 2))];
      if (a != b && b != c && a != c) kept.insert(kept.end(), {a, b, c});
    }
    return Eigen::Map<const Faces>(kept.data(), static_cast<Eigen::Index>(kept.size() / 3), 3);
  }

  // Each face's target: equilateral, with the surface area its corners stand for; or, once the
  // whole mesh is in, the true face's area and shape.
  std::vector<StretchTarget> level_targets(Eigen::Index active, const Faces& faces) const {
    std::vector<StretchTarget> targets(static_cast<std::size_t>(faces.rows()));
    if (active == n_) {
      for (Eigen::Index f = 0; f < faces.rows(); ++f)
        targets[static_cast<std::size_t>(f)] =
            face_target(V_.row(faces(f, 0)), V_.row(faces(f, 1)), V_.row(faces(f, 2)));
      return targets;
    }
    const std::vector<int> rep = representatives(active);
    std::vector<double> mass(static_cast<std::size_t>(n_), 0.0);
    std::vector<int> valence(static_cast<std::size_t>(n_), 0);
    for (Eigen::Index v = 0; v < n_; ++v)
      mass[static_cast<std::size_t>(rep[static_cast<std::size_t>(v)])] += vertex_area_[v];
    for (Eigen::Index f = 0; f < faces.rows(); ++f)
      for (int k = 0; k < 3; ++k) ++valence[static_cast<std::size_t>(faces(f, k))];
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      double m = 0;
      for (int k = 0; k < 3; ++k) {
        const auto v = static_cast<std::size_t>(faces(f, k));
        m += mass[v] / valence[v];  // each vertex's area shared by its faces
      }
      targets[static_cast<std::size_t>(f)] = equilateral_target(m);
    }
    return targets;
  }

  // The one-ring of vertex v when it is re-inserted (counter-clockwise, its partner first).
  std::pair<const int*, int> ring(int v) const {
    const auto i = static_cast<std::size_t>(collapse_of_[static_cast<std::size_t>(v)]);
    const int begin = pm_.ring_offsets[i], end = pm_.ring_offsets[i + 1];
    return {pm_.ring.data() + begin, end - begin};
  }

 private:
  // The tetrahedron on the sphere, regular, wound like the mesh.
  void place_base() {
    const double r = 1.0 / std::sqrt(3.0);
    const Eigen::Vector3d corners[4] = {{r, r, r}, {r, -r, -r}, {-r, r, -r}, {-r, -r, r}};
    for (int k = 0; k < 4; ++k) S_.row(pm_.base_vertices[static_cast<std::size_t>(k)]) = corners[k].transpose();
    const auto oriented = [&] {
      const auto& B = pm_.base_faces;
      return orientation_sign(S_.row(B(0, 0)), S_.row(B(0, 1)), S_.row(B(0, 2))) > 0;
    };
    if (!oriented()) {  // the mirror image: swap two corners
      S_.row(pm_.base_vertices[0]) = corners[1].transpose();
      S_.row(pm_.base_vertices[1]) = corners[0].transpose();
    }
    for (Eigen::Index f = 0; f < 4; ++f) {
      const auto& B = pm_.base_faces;
      if (orientation_sign(S_.row(B(f, 0)), S_.row(B(f, 1)), S_.row(B(f, 2))) <= 0)
        throw std::logic_error("the base tetrahedron is not consistently wound");
    }
  }

  const Vertices& V_;
  const Faces& F_;
  const ProgressiveMesh& pm_;
  std::vector<int> order_;
  Eigen::Index n_;
  std::vector<int> parent_, collapse_of_;
  Eigen::VectorXd vertex_area_;
  Vertices S_;
  std::vector<double> step_;
};

// True when x is strictly inside the spherical kernel of the ring: every triangle
// (x, ring[j], ring[j+1]) positively oriented, decided exactly.
bool in_kernel(const Vertices& S, const int* ring, int k, const Eigen::Vector3d& x) {
  for (int j = 0; j < k; ++j)
    if (orientation_sign(x, S.row(ring[j]), S.row(ring[(j + 1) % k])) <= 0) return false;
  return true;
}

// A point of the kernel next to the ring's first vertex (the collapse partner): the kernel
// always holds points of the interior angle's bisector arbitrarily close to it, since the
// partner's fan over the same polygon was positive.
std::optional<Eigen::Vector3d> near_partner(const Vertices& S, const int* ring, int k) {
  const Eigen::Vector3d n = S.row(ring[0]).transpose();
  const Eigen::Vector3d to_first = S.row(ring[1]).transpose() - n, to_last = S.row(ring[k - 1]).transpose() - n;
  const Eigen::Vector3d u = (to_first - to_first.dot(n) * n).normalized();
  const Eigen::Vector3d w = n.cross(u);
  double angle = std::atan2(to_last.dot(w), to_last.dot(u));  // counter-clockwise from the first
  if (angle <= 0) angle += 2 * M_PI;
  const Eigen::Vector3d bisector = std::cos(angle / 2) * u + std::sin(angle / 2) * w;
  double eps = 0.5 * std::min(to_first.norm(), to_last.norm());
  for (int i = 0; i < 60; ++i, eps *= 0.5) {
    const Eigen::Vector3d x = (n + eps * bisector).normalized();
    if (in_kernel(S, ring, k, x)) return x;
  }
  return std::nullopt;
}

// Where a re-inserted vertex goes: its ring's centroid if that is in the kernel, else as far
// towards it from a point next to its partner as the kernel allows.
std::optional<Eigen::Vector3d> place_in_kernel(const Vertices& S, const int* ring, int k, bool& fell_back) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int j = 0; j < k; ++j) centroid += S.row(ring[j]).transpose();
  centroid.normalize();
  fell_back = false;
  if (centroid.allFinite() && in_kernel(S, ring, k, centroid)) return centroid;
  fell_back = true;
  auto start = near_partner(S, ring, k);
  if (!start) return std::nullopt;
  if (!centroid.allFinite()) return start;
  for (double t = 0.5; t > 0.03; t *= 0.5) {
    const Eigen::Vector3d x = ((1 - t) * *start + t * centroid).normalized();
    if (in_kernel(S, ring, k, x)) return x;
  }
  return start;
}

// One level of the refinement, ready for descent passes.
struct Level {
  Level(const Refinement& r, Eigen::Index active)
      : Level(r, active, std::vector<int>(r.order().begin(), r.order().begin() + active)) {}
  Level(const Refinement& r, Eigen::Index active, std::vector<int> movable_vertices)
      : faces(r.level_faces(active)),
        problem(faces, r.level_targets(active, faces), r.size(), movable_vertices),
        movable(std::move(movable_vertices)) {}
  void descend(Refinement& r, int sweeps, StretchDescentOptions options, const JobControl* control,
               const std::function<void(double)>& progress = {}) {
    options.sweeps = sweeps;
    descend_stretch(r.positions(), problem, r.steps(), options, control, progress);
  }
  Faces faces;
  StretchProblem problem;
  std::vector<int> movable;
};

// The vertices within `radius` edges of a ring, in the level with `active` vertices in, in a
// fixed order (breadth first from the ring).
std::vector<int> neighbourhood(const Refinement& r, Eigen::Index active, const int* ring, int k, int radius) {
  const Faces faces = r.level_faces(active);
  const VertexFaces vf = vertex_faces(faces, r.size());
  std::vector<int> found(ring, ring + k);
  std::vector<char> seen(static_cast<std::size_t>(r.size()), 0);
  for (const int v : found) seen[static_cast<std::size_t>(v)] = 1;
  std::size_t frontier = 0;
  for (int step = 1; step < radius; ++step) {
    const std::size_t end = found.size();
    for (; frontier < end; ++frontier) {
      const int v = found[frontier];
      for (int i = vf.offsets[v]; i < vf.offsets[v + 1]; ++i)
        for (int c = 0; c < 3; ++c) {
          const int u = faces(vf.faces[i], c);
          if (!seen[static_cast<std::size_t>(u)]) {
            seen[static_cast<std::size_t>(u)] = 1;
            found.push_back(u);
          }
        }
    }
  }
  return found;
}

// A few steps of the new vertex alone towards equal, well-shaped triangles around it: a vertex
// that had to go next to its partner does not stay there to squeeze the next insertions.
void settle(Refinement& r, int v, const int* ring, int k, const ProgressiveSphereMapOptions& options) {
  VertexStar star;
  for (int j = 0; j < k; ++j) {
    star.others.push_back({ring[j], ring[(j + 1) % k]});
    star.targets.push_back(equilateral_target(1.0));
  }
  improve_vertex(r.positions(), v, star, options.settle_steps, options.descent);
}

// Descent passes for a level of `active` vertices that would get `sweeps` at a moderate size.
int sweeps_for(const ProgressiveSphereMapOptions& options, Eigen::Index active, int sweeps) {
  if (active <= options.large_vertices) return sweeps;
  const double scale = static_cast<double>(options.large_vertices) / static_cast<double>(active);
  return std::max(2, static_cast<int>(std::lround(sweeps * scale)));
}

// Places vertex v in its ring's kernel and settles it there; false when the kernel is too thin
// for doubles (nothing is then written). Reads only the ring's positions, writes only v's.
bool insert_vertex(Refinement& r, int v, const ProgressiveSphereMapOptions& options, bool& fell_back) {
  const auto [ring, k] = r.ring(v);
  const auto x = place_in_kernel(r.positions(), ring, k, fell_back);
  if (!x) return false;
  r.positions().row(v) = x->transpose();
  settle(r, v, ring, k, options);
  return true;
}

// Inserts the order's [begin, end) one by one, as the collapses are undone: a vertex whose
// kernel is too thin first gets a growing neighbourhood relaxed.
void insert_in_order(Refinement& r, Eigen::Index begin, Eigen::Index end, const ProgressiveSphereMapOptions& options,
                     const JobControl* control, ProgressiveSphereMap& result) {
  for (Eigen::Index j = begin; j < end; ++j) {
    const int v = r.order()[static_cast<std::size_t>(j)];
    const auto [ring, k] = r.ring(v);
    bool fell_back = false;
    bool placed = insert_vertex(r, v, options, fell_back);
    for (int radius = 1; !placed && radius <= 6; ++radius) {
      // A kernel too thin for doubles (thin wedges around the partner, vertices crowded by
      // earlier placements): fatten a growing neighbourhood (without v) by Tutte steps and the
      // descent, then try again.
      ++result.relaxations;
      Level here(r, j, neighbourhood(r, j, ring, k, radius));
      for (int round = 0; round < 10; ++round)
        for (const int u : here.movable) step_towards_neighbours(r.positions(), u, here.problem);
      here.descend(r, 5, options.descent, control);
      placed = insert_vertex(r, v, options, fell_back);
    }
    if (!placed) throw SphereParamError("vertex " + std::to_string(v) + " found no place in the kernel of its ring");
    result.kernel_fallbacks += fell_back ? 1 : 0;
  }
}

// The order's [begin, end) in waves: a vertex goes one wave after the last of its ring's vertices
// inserted in the range, so a wave's vertices read none of the positions the wave writes, and
// inserting a wave at once gives what inserting its vertices in order would, bit for bit.
std::vector<std::vector<int>> insertion_waves(const Refinement& r, Eigen::Index begin, Eigen::Index end) {
  std::vector<int> wave_of(static_cast<std::size_t>(r.size()), -1);
  std::vector<std::vector<int>> waves;
  for (Eigen::Index j = begin; j < end; ++j) {
    const int v = r.order()[static_cast<std::size_t>(j)];
    const auto [ring, k] = r.ring(v);
    int wave = 0;
    for (int i = 0; i < k; ++i) wave = std::max(wave, wave_of[static_cast<std::size_t>(ring[i])] + 1);
    wave_of[static_cast<std::size_t>(v)] = wave;
    if (static_cast<std::size_t>(wave) >= waves.size()) waves.resize(static_cast<std::size_t>(wave) + 1);
    waves[static_cast<std::size_t>(wave)].push_back(v);
  }
  return waves;
}

// Inserts the order's [begin, end) wave by wave, each wave's vertices in parallel. False when a
// kernel was too thin: a relaxation moves vertices the later insertions read, so the caller then
// inserts the range in order (over the positions written here, which no insertion reads before
// writing them again). `progress` hears the count inserted, from one thread at a time.
bool insert_in_waves(Refinement& r, Eigen::Index begin, Eigen::Index end, const ProgressiveSphereMapOptions& options,
                     const JobControl* control, ProgressiveSphereMap& result,
                     const std::function<void(std::int64_t)>& progress) {
  std::atomic<std::int64_t> inserted{0};
  std::atomic<std::size_t> fell_back{0};
  std::atomic<bool> stuck{false};
  std::mutex reporting;
  for (const std::vector<int>& wave : insertion_waves(r, begin, end)) {
    poll(control);
    const auto size = static_cast<std::int64_t>(wave.size());
    const int threads = static_cast<int>(std::clamp<std::int64_t>(size / kWaveGrain, 1, threads_of(control)));
    // Slices taken as threads come free.
    parallel_for_each((size + kWaveSlice - 1) / kWaveSlice, threads, [&](std::int64_t slice) {
      std::size_t fallbacks = 0;
      for (std::int64_t i = slice * kWaveSlice; i < std::min(size, (slice + 1) * kWaveSlice) && !stuck; ++i) {
        bool fell = false;
        if (!insert_vertex(r, wave[static_cast<std::size_t>(i)], options, fell)) stuck = true;
        fallbacks += fell ? 1 : 0;
      }
      fell_back += fallbacks;
      inserted += std::min(size, (slice + 1) * kWaveSlice) - slice * kWaveSlice;
      // By whichever thread is free to: one held up by others' load (the caller too) delays no report.
      if (const std::unique_lock lock(reporting, std::try_to_lock); lock) progress(inserted);
    });
    if (stuck) return false;
  }
  result.kernel_fallbacks += fell_back;
  return true;
}

}  // namespace

ProgressiveSphereMap progressive_sphere_map(const Vertices& V, const Faces& F,
                                            const ProgressiveSphereMapOptions& options, const JobControl* control,
                                            const std::string& stage, double progress_from, double progress_to) {
  ProgressiveSphereMap result;
  ProgressMeter meter(control, stage, progress_from, progress_to);
  const auto start = Clock::now();
  // Progress: coarsening 15 %, refinement 55 %, the final passes 30 % (as they take on the bunny).
  const ProgressiveMesh pm = coarsen_to_tetrahedron(V, F, control, [&meter](double f) { meter.update(0.15 * f); });
  result.collapses = pm.collapses();
  result.coarsen_seconds = seconds_since(start);
  meter.update(0.15);

  const auto refine_start = Clock::now();
  Refinement r(V, F, pm);
  const Eigen::Index n = r.size();
  // Each doubling of the vertex count is inserted, then descended as a level.
  for (Eigen::Index active = 4, next_level = std::min<Eigen::Index>(8, n); active < n;
       active = next_level, next_level = std::min<Eigen::Index>(2 * active, n)) {
    const auto refined = [&](Eigen::Index in) {
      return 0.15 + 0.55 * static_cast<double>(in) / static_cast<double>(n);
    };
    if (!insert_in_waves(r, active, next_level, options, control, result,
                         [&](std::int64_t count) { meter.update(refined(active + count)); }))
      insert_in_order(r, active, next_level, options, control, result);
    const double at = refined(next_level);
    meter.update(at);
    if (next_level == n) break;  // the whole mesh gets the final passes
    Level level(r, next_level);
    const int sweeps = next_level <= options.coarse_vertices ? options.coarse_sweeps
                                                             : sweeps_for(options, next_level, options.level_sweeps);
    level.descend(r, sweeps, options.descent, control, [&](double) { meter.update(at); });  // keeps reports going
    if (options.on_level) options.on_level(r.positions(), level.faces);
    ++result.levels;
  }
  result.refine_seconds = seconds_since(refine_start);

  const auto final_start = Clock::now();
  Level whole(r, n);
  const int final_sweeps = sweeps_for(options, n, options.final_sweeps);
  whole.descend(r, final_sweeps, options.descent, control, [&](double f) { meter.update(0.7 + 0.3 * f); });
  meter.update(1.0);
  if (options.on_level) options.on_level(r.positions(), whole.faces);
  ++result.levels;
  result.final_seconds = seconds_since(final_start);
  result.S = std::move(r.positions());
  return result;
}

}  // namespace meshmark
