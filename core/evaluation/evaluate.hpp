#pragma once
// The robustness evaluation: meshes × schemes × attacks × trials, each trial with its own random
// key and 64-bit payload, reproducible from the trial number. Reports bit error rates, detection,
// distortion, false alarms, the noise bound and BER against strength; `check_requirements` says
// which of the promised figures were missed.

#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/attacks/attack_registry.hpp"
#include "core/watermark/watermark_options.hpp"

namespace meshmark {

struct EvalRow {
  std::string table;  ///< "paper" (Jin et al.'s Table 1 layout) or "benchmark" (Wang et al. 2010)
  std::string label;
  AttackChain chain;
};

struct EvalScheme {
  std::string label;
  WatermarkOptions options;
  bool benchmark = false;  ///< also runs the benchmark table (the default scheme does)
};

struct EvalOptions {
  std::vector<std::filesystem::path> meshes;
  int trials = 5;
  bool quick = false;        ///< the CI subset: the spread scheme on the rows the requirements name, 1 trial
  int threads = 2;           ///< trials run at once (each one's parallel steps share the hardware's threads)
  bool force_bumps = false;  ///< every mesh on bumps, for the side-by-side with the sphere
  std::vector<double> strength_sweep = {0.03, 0.05, 0.08, 0.12, 0.2};  ///< for the 0.6 % noise row
  /// The marks' strength (% of the diagonal). Below the default the promise is the mild set
  /// (required_at_low_strength).
  double strength_percent = WatermarkOptions{}.strength_percent;
  /// Null detections per mesh besides the trials' (half unmarked, half a wrong key, each with its
  /// own key and expected payload): the measured false-alarm rate and null p-value distribution.
  int null_detections = 0;
  std::set<std::string> tables;  ///< the attack tables run ("paper", "benchmark", "beyond"); empty: all
  std::function<void(const std::string&)> progress;
};

struct EvalOutcome {
  std::string mesh, scheme, table, row;
  int trial = 0;
  double ber = 0;       ///< payload bit error rate
  double raw_ber = -1;  ///< paper scheme: per-carrier error rate (its Table 1 measure)
  bool detected = false;
  double z = 0, log10_p = 0;
};

struct EvalDistortion {
  std::string mesh, scheme;
  int trial = 0;
  double mrms = 0, hausdorff = 0;  ///< relative to the bbox diagonal
};

struct EvalFalseAlarm {
  std::string mesh, kind;  ///< "unmarked" or "wrong key"
  int trial = 0;
  bool detected = false;
  double log10_p = 0;
};

struct EvalSweep {
  std::string mesh;
  int trial = 0;
  double strength = 0, mrms = 0, ber = 0;
};

struct EvalMesh {
  std::string name;
  long long vertices = 0;
  std::string basis;            ///< what carries the watermark (sphere, sphere-filled, bumps)
  double rms_displacement = 0;  ///< of the default scheme, relative to the bbox diagonal
  /// For each noise row ("table/label"): σ of the noise along a normal, relative to the diagonal.
  std::map<std::string, double> noise_sigma;
};

struct EvalResults {
  EvalOptions options;
  std::vector<EvalMesh> meshes;
  std::vector<EvalScheme> schemes;
  std::vector<EvalRow> rows;
  std::vector<EvalOutcome> outcomes;
  std::vector<EvalDistortion> distortions;
  std::vector<EvalFalseAlarm> false_alarms;
  std::vector<EvalFalseAlarm> nulls;  ///< the null_detections (trial = their index)
  std::vector<EvalSweep> sweep;
  double seconds = 0;
};

std::vector<EvalRow> paper_table_rows();
std::vector<EvalRow> benchmark_table_rows();
/// Beyond the benchmark: crops to half and more with a similarity, bends and twists.
std::vector<EvalRow> beyond_table_rows();
std::vector<EvalScheme> evaluation_schemes(double strength_percent = WatermarkOptions{}.strength_percent);

/// Runs the matrix. Throws if a mesh cannot be read or watermarked.
EvalResults evaluate(const EvalOptions& options);

/// The noise bound for a noise row on a mesh: w·√(N/b)/σ with w the watermark's RMS displacement,
/// N vertices, b payload bits, σ the noise's standard deviation along a normal; 0 for other rows.
double noise_snr_bound(const EvalMesh& mesh, const EvalRow& row, int payload_bits = 64);

/// Whether the default scheme promises BER 0 for this row on this mesh at the default strength.
bool required(const std::string& mesh, const std::string& table, const std::string& row);

/// The same below the default strength (0.02 %): the benchmark's mild attacks only.
bool required_at_low_strength(const std::string& mesh, const std::string& table, const std::string& row);

/// The promised figures that were missed, in words (empty when all hold).
std::vector<std::string> check_requirements(const EvalResults& results);

}  // namespace meshmark
