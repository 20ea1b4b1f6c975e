#pragma once
// The pipeline benchmark: every stage of a cold embed (new model), a warm embed (prepared model)
// and a detection, timed and with its peak resident memory. Each run happens in a forked child,
// so runs do not share caches or heap, and a large mesh's memory is returned between runs.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace meshmark {

struct BenchmarkOptions {
  std::vector<std::filesystem::path> meshes;
  /// Also benchmark the first mesh Loop-subdivided this many times (0: not); bunny, 2 → 557k vertices.
  int subdivided_steps = 2;
  int runs = 3;     ///< runs per mesh; medians are reported
  int threads = 0;  ///< threads of the pipeline's parallel steps; 0: the hardware's, at most 8
  std::function<void(const std::string&)> progress;
};

/// One stage of one run.
struct StageSample {
  std::string stage;
  double seconds = 0;
  double peak_mib = 0;  ///< the process's peak resident memory during the stage
};

struct StageFigures {
  std::string stage;
  std::vector<double> seconds;  ///< per run
  double median_seconds = 0;
  double median_peak_mib = 0;
  /// Median over runs of the stage's time ÷ that run's load + write (the floor): a ratio a noisy
  /// host changes far less than seconds.
  double median_floor_ratio = 0;
};

struct MeshFigures {
  std::string mesh;
  long long vertices = 0, faces = 0;
  std::vector<StageFigures> stages;  ///< in pipeline order; totals are "total.*"
  double peak_mib = 0;               ///< the largest stage peak
  /// Share of the machine's CPU time the hypervisor took (steal) during this mesh's runs: on a
  /// shared VM, times are inflated by about 1 / (1 − steal).
  double steal_fraction = 0;
  const StageFigures* find(const std::string& stage) const;
};

/// The stages, in order, with what each covers.
const std::vector<std::pair<std::string, std::string>>& benchmark_stages();

/// One run in this process: loads `mesh`, prepares, embeds, writes, embeds again on the
/// prepared model, and detects in a similarity-transformed copy; on `threads` threads (0: the hardware's).
std::vector<StageSample> measure_pipeline_once(const std::filesystem::path& path, int threads);

/// Runs the benchmark (each run in a forked child). Throws std::runtime_error if a run fails.
std::vector<MeshFigures> run_benchmark(const BenchmarkOptions& options);

/// `mesh` Loop-subdivided `steps` times, written to `out` as binary PLY.
void write_subdivided(const std::filesystem::path& mesh, int steps, const std::filesystem::path& out);

/// Least-squares slope of log(y) against log(x): the exponent of y ∝ x^e.
double growth_exponent(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace meshmark
