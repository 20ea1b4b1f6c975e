#include "core/evaluation/benchmark.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/attacks/similarity_transform.hpp"
#include "core/attacks/subdivide.hpp"
#include "core/evaluation/host_load.hpp"
#include "core/io/document_surface.hpp"
#include "core/io/read_mesh.hpp"
#include "core/io/write_mesh.hpp"
#include "core/util/process_memory.hpp"
#include "core/verification/read_back.hpp"
#include "core/verification/verify_copy.hpp"
#include "core/watermark/detect_stages.hpp"
#include "core/watermark/nuisance_fields.hpp"
#include "core/watermark/prepared_model.hpp"
#include "core/watermark/watermark.hpp"

namespace meshmark {

namespace {

using Clock = std::chrono::steady_clock;
constexpr const char* kKey = "benchmark key";
constexpr const char* kOtherKey = "benchmark key, another owner";

// Closes one stage and opens the next: its time, and the peak resident memory since it began.
class StageClock {
 public:
  explicit StageClock(std::vector<StageSample>& out) : out_(out) {}
  void begin(const std::string& stage) {
    end();
    stage_ = stage;
    reset_peak_resident();
    start_ = Clock::now();
  }
  void end() {
    if (stage_.empty()) return;
    const double seconds = std::chrono::duration<double>(Clock::now() - start_).count();
    out_.push_back({stage_, seconds, static_cast<double>(peak_resident_bytes().value_or(0)) / (1024.0 * 1024.0)});
    stage_.clear();
  }
  // A control whose checkpoints open the stages named in `names` (pipeline stage → ours); a
  // stage's own progress reports leave it open.
  JobControl control(const std::map<std::string, std::string>& names, int threads) {
    JobControl c;
    c.threads = threads;
    c.report = [this, names](const std::string& stage, double) {
      const auto it = names.find(stage);
      if (it != names.end() && it->second != stage_) begin(it->second);
    };
    return c;
  }

 private:
  std::vector<StageSample>& out_;
  std::string stage_;
  Clock::time_point start_;
};

// A whole operation as one "total.*" sample (its peak is the largest of its stages).
struct Total {
  std::string name;
  Clock::time_point start = Clock::now();
  std::size_t first_stage;
};

void close_total(std::vector<StageSample>& out, const Total& total) {
  double peak = 0;
  for (std::size_t i = total.first_stage; i < out.size(); ++i) peak = std::max(peak, out[i].peak_mib);
  const double seconds = std::chrono::duration<double>(Clock::now() - total.start).count();
  out.push_back({total.name, seconds, peak});
}

std::filesystem::path scratch_file(const std::string& extension) {
  return std::filesystem::temp_directory_path() / ("meshmark-bench-" + std::to_string(::getpid()) + "-" +
                                                   std::to_string(Clock::now().time_since_epoch().count()) + extension);
}

// Runs measure_pipeline_once in a child; the samples come back through a pipe as text.
std::vector<StageSample> run_in_child(const std::filesystem::path& mesh, int threads) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("benchmark: cannot create a pipe");
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("benchmark: cannot fork");
  if (pid == 0) {
    ::close(fds[0]);
    int status = 0;
    std::ostringstream text;
    try {
      for (const StageSample& s : measure_pipeline_once(mesh, threads))
        text << s.stage << ' ' << s.seconds << ' ' << s.peak_mib << '\n';
    } catch (const std::exception& e) {
      text << "error " << e.what() << '\n';
      status = 1;
    }
    const std::string bytes = text.str();
    std::size_t sent = 0;
    while (sent < bytes.size()) {
      const ssize_t n = ::write(fds[1], bytes.data() + sent, bytes.size() - sent);
      if (n <= 0) break;
      sent += static_cast<std::size_t>(n);
    }
    ::_exit(status);
  }
  ::close(fds[1]);
  std::string text;
  char buffer[4096];
  ssize_t n;
  while ((n = ::read(fds[0], buffer, sizeof buffer)) > 0) text.append(buffer, static_cast<std::size_t>(n));
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("benchmark run on " + mesh.string() +
                             " failed: " + (text.empty() ? "the child died" : text));
  std::vector<StageSample> samples;
  std::istringstream lines(text);
  StageSample s;
  while (lines >> s.stage >> s.seconds >> s.peak_mib) samples.push_back(s);
  return samples;
}

// The floor of one run: reading the mesh and writing its copy, the least any tool does with it.
double floor_seconds(const std::vector<StageSample>& run) {
  double seconds = 0;
  for (const StageSample& s : run)
    if (s.stage == "load" || s.stage == "write") seconds += s.seconds;
  return seconds;
}

MeshFigures summarize(const std::string& name, const Mesh& mesh, const std::vector<std::vector<StageSample>>& runs) {
  MeshFigures figures;
  figures.mesh = name;
  figures.vertices = mesh.V.rows();
  figures.faces = mesh.F.rows();
  for (std::size_t i = 0; i < runs.front().size(); ++i) {
    StageFigures stage;
    stage.stage = runs.front()[i].stage;
    std::vector<double> peaks, ratios;
    for (const auto& run : runs) {
      stage.seconds.push_back(run.at(i).seconds);
      peaks.push_back(run.at(i).peak_mib);
      const double floor = floor_seconds(run);
      ratios.push_back(floor > 0 ? run.at(i).seconds / floor : 0.0);
    }
    stage.median_seconds = median(stage.seconds);
    stage.median_peak_mib = median(peaks);
    stage.median_floor_ratio = median(ratios);
    figures.peak_mib = std::max(figures.peak_mib, stage.median_peak_mib);
    figures.stages.push_back(stage);
  }
  return figures;
}

}  // namespace

const StageFigures* MeshFigures::find(const std::string& stage) const {
  for (const StageFigures& s : stages)
    if (s.stage == stage) return &s;
  return nullptr;
}

const std::vector<std::pair<std::string, std::string>>& benchmark_stages() {
  static const std::vector<std::pair<std::string, std::string>> stages = {
      {"load", "read the mesh file"},
      {"validate", "validation, outward orientation, normals, vertex areas"},
      {"parameterize", "bijective spherical map (progressive mesh, stretch descent, proof)"},
      {"grid_and_sampling", "grid (shared per level) and sampling the mesh on it"},
      {"bumps", "multiscale bumps on the mesh itself (meshes the sphere cannot take)"},
      {"embed.plan", "carriers and amplitudes (includes a forward transform of the sampled geometry)"},
      {"embed.synthesis", "inverse transform of the change and mapping back to the vertices"},
      {"embed.apply", "moving the vertices along their normals"},
      {"write", "write the watermarked mesh (same format as the input)"},
      {"total.cold_embed", "a new model: load to write"},
      {"forward_transform", "forward transform of the sampled geometry (3 channels), alone"},
      {"total.warm_embed.new_key", "a prepared model, a key it has no carrier plan for: embed and write"},
      {"total.warm_embed",
       "a prepared model, a key planned before (an owner's every copy after the first): embed and write"},
      {"verify",
       "the copy read back from its bytes and read by the detector as written and after a re-save and a similarity "
       "(model data kept, as in the daemon)"},
      {"verify.proven",
       "the same once registration is proven for the model (the daemon's every copy after the first): both "
       "readings in place"},
      {"detect.model_data",
       "once per model: registration target (dense samples, k-d tree, AABB tree), nuisance fields"},
      {"detect.align", "registration to the original (PCA candidates, trimmed ICP)"},
      {"detect.read", "the suspect's offset at the original's vertices (by projection), nuisances removed"},
      {"detect.estimate", "carrier estimates: matched filter and regularized solves"},
      {"detect.decode", "Viterbi decoding of each estimate, the choice of reading, the decision"},
      {"total.detect", "a detection on a prepared model"},
  };
  return stages;
}

// The marked copy as `embed` writes it: the document with moved positions (its main file); the
// files in memory are returned.
DocumentFiles write_marked_document(const MeshDocument& document, const WeldedSurface& surface, const Mesh& marked,
                                    const std::filesystem::path& path) {
  const MovedSlots moved = move_slots(document, surface, marked.V);
  DocumentFiles files = document.write(moved.positions, moved.rotations);
  std::ofstream(path, std::ios::binary) << files.at("");
  return files;
}

// The self-check of a copy, as embed and the daemon run it (verify_copy.hpp).
void verify_written(const MeshDocument& document, const DocumentFiles& files, const std::filesystem::path& original,
                    const PreparedModel& model, const RegistrationTarget& target, const Bits& payload, int threads,
                    const VerifyOptions& verify) {
  Mesh as_written = read_back(files, document.format(), [&](const std::string& uri) {
    return read_file_bytes(original.parent_path() / percent_decoded(uri), ReadOptions{}.max_file_bytes);
  });
  JobControl control;
  control.threads = threads;
  const CopyVerification v = verify_copy(model, target, std::move(as_written), kKey, payload, {}, verify, &control);
  require_readable(v, payload);
}

std::vector<StageSample> measure_pipeline_once(const std::filesystem::path& path, int threads) {
  std::vector<StageSample> out;
  StageClock clock(out);
  const auto marked_path = scratch_file(path.extension().string());

  Total cold{"total.cold_embed", Clock::now(), out.size()};
  clock.begin("load");
  const auto document = read_document_file(path);
  const WeldedSurface surface = document_surface(*document);
  const Mesh& mesh = surface.mesh;
  JobControl prepare = clock.control(
      {{"validate", "validate"}, {"parameterize", "parameterize"}, {"sample", "grid_and_sampling"}, {"basis", "bumps"}},
      threads);
  const PreparedModel model = prepare_model(mesh, {}, &prepare);
  JobControl embed = clock.control({{embed_stage::plan, std::string("embed.") + embed_stage::plan},
                                    {embed_stage::synthesis, std::string("embed.") + embed_stage::synthesis},
                                    {embed_stage::apply, std::string("embed.") + embed_stage::apply}},
                                   threads);
  const EmbedResult marked = embed_watermark(model, kKey, bits_from_hex("0123456789abcdef"), {}, &embed);
  clock.begin("write");
  write_marked_document(*document, surface, marked.mesh, marked_path);
  clock.end();
  close_total(out, cold);
  std::filesystem::remove(marked_path);

  if (model.spherical()) {  // a bump model has no grid to transform
    clock.begin("forward_transform");
    const SphericalWavelet wavelet(*model.grid, model.level(), WatermarkOptions{}.wavelet);
    Eigen::MatrixXd geometry = model.sampling.positions;
    wavelet.forward(geometry);
    clock.end();
  }

  // Warm embeds as one stage each: embed and write on the prepared model, first under a key the
  // model has not planned for, then under the cold embed's (planned: the daemon's every copy for an
  // owner after the first). The copy verified below is the last.
  DocumentFiles written;
  for (const bool planned : {false, true}) {
    reset_peak_resident();
    Total warm{planned ? "total.warm_embed" : "total.warm_embed.new_key", Clock::now(), out.size()};
    JobControl warm_control;
    warm_control.threads = threads;
    const EmbedResult again =
        embed_watermark(model, planned ? kKey : kOtherKey, bits_from_hex("fedcba9876543210"), {}, &warm_control);
    written = write_marked_document(*document, surface, again.mesh, marked_path);
    out.push_back({warm.name, std::chrono::duration<double>(Clock::now() - warm.start).count(),
                   static_cast<double>(peak_resident_bytes().value_or(0)) / (1024.0 * 1024.0)});
    std::filesystem::remove(marked_path);
  }

  const Mesh suspect = transform_mesh(marked.mesh, random_similarity(marked.mesh, 7));
  clock.begin("detect.model_data");  // once per model; the daemon keeps them with the model
  const RegistrationTarget target(model.outward_mesh());
  nuisance_fields(model, threads);
  clock.end();
  for (const bool proven : {false, true}) {
    clock.begin(proven ? "verify.proven" : "verify");
    verify_written(*document, written, path, model, target, bits_from_hex("fedcba9876543210"), threads,
                   {.registration_proven = proven});
    clock.end();
  }
  Total detect{"total.detect", Clock::now(), out.size()};
  JobControl detection = clock.control({{detect_stage::align, std::string("detect.") + detect_stage::align},
                                        {detect_stage::read, std::string("detect.") + detect_stage::read},
                                        {detect_stage::estimate, std::string("detect.") + detect_stage::estimate},
                                        {detect_stage::decode, std::string("detect.") + detect_stage::decode}},
                                       threads);
  const DetectResult found = detect_watermark(model, suspect, kKey, {}, &target, &detection);
  clock.end();
  close_total(out, detect);
  if (!found.detected) throw std::runtime_error("the benchmark's watermark was not detected");
  return out;
}

std::vector<MeshFigures> run_benchmark(const BenchmarkOptions& options) {
  std::vector<std::pair<std::string, std::filesystem::path>> inputs;
  for (const auto& m : options.meshes) inputs.emplace_back(m.filename().string(), m);
  std::filesystem::path generated;
  if (options.subdivided_steps > 0 && !options.meshes.empty()) {
    if (options.progress)
      options.progress("generating " + options.meshes.front().filename().string() + ", Loop-subdivided");
    generated = scratch_file(".ply");
    write_subdivided(options.meshes.front(), options.subdivided_steps, generated);
    inputs.emplace_back(
        options.meshes.front().stem().string() + "-loop" + std::to_string(options.subdivided_steps) + ".ply",
        generated);
  }
  std::vector<MeshFigures> figures;
  try {
    for (const auto& [name, path] : inputs) {
      std::vector<std::vector<StageSample>> runs;
      const CpuJiffies before = cpu_jiffies();
      for (int r = 0; r < options.runs; ++r) {
        if (options.progress)
          options.progress(name + ": run " + std::to_string(r + 1) + " of " + std::to_string(options.runs));
        runs.push_back(run_in_child(path, options.threads));
      }
      const CpuJiffies after = cpu_jiffies();
      figures.push_back(summarize(name, read_surface(path), runs));
      figures.back().steal_fraction = steal_fraction(before, after);
    }
  } catch (...) {
    if (!generated.empty()) std::filesystem::remove(generated);
    throw;
  }
  if (!generated.empty()) std::filesystem::remove(generated);
  return figures;
}

void write_subdivided(const std::filesystem::path& mesh, int steps, const std::filesystem::path& out) {
  write_mesh(out, subdivide(read_mesh(mesh).mesh, SubdivisionScheme::loop, steps), {.binary = true});
}

double growth_exponent(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = std::min(x.size(), y.size());
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) {
    mx += std::log(x[i]) / n;
    my += std::log(y[i]) / n;
  }
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sxy += (std::log(x[i]) - mx) * (std::log(y[i]) - my);
    sxx += (std::log(x[i]) - mx) * (std::log(x[i]) - mx);
  }
  return sxx > 0 ? sxy / sxx : 0.0;
}

}  // namespace meshmark
