// meshmark embed IN OUT --key KEY --payload HEX [scheme options] [--json]

#include <chrono>
#include <cstdio>
#include <random>
#include <set>
#include <ctime>
#include <filesystem>
#include <future>
#include <iostream>
#include <optional>
#include <stdexcept>

#include "client/commands/commands.hpp"
#include "client/commands/copy_record_files.hpp"
#include "client/commands/stored_originals.hpp"
#include "client/commands/document_files.hpp"
#include "client/commands/prepared_cache.hpp"
#include "client/commands/recipients.hpp"
#include "client/commands/stage_seconds.hpp"
#include "client/commands/watermark_options_cli.hpp"
#include "client/commands/run_options_cli.hpp"
#include "client/terminal_progress.hpp"
#include "core/io/document_surface.hpp"
#include "core/io/mesh_document.hpp"
#include "core/io/write_mesh.hpp"
#include "core/metrics/compare_meshes.hpp"
#include "core/util/atomic_file.hpp"
#include "core/util/input_error.hpp"
#include "core/util/parallel_for.hpp"
#include "core/verification/read_back.hpp"
#include "core/verification/verify_copy.hpp"
#include "core/watermark/carrier_cache.hpp"
#include "core/watermark/prepared_model_io.hpp"
#include "core/watermark/spread_plan.hpp"
#include "core/watermark/watermark.hpp"
#include "proto/copy_record.hpp"
#include "proto/json_text.hpp"
#include "proto/core_json.hpp"

namespace meshmark::cli {

namespace {

struct EmbedArgs {
  std::string in, out, key, payload;
  std::string recipient;                ///< named in the copy's record
  std::vector<std::string> recipients;  ///< a copy for each, into the folder `out`
  std::string recipients_file;
  SchemeArgs scheme;
  bool json = false;
  RunArgs run;
  CacheArgs cache;
  std::string record;   ///< empty: in the records folder
  std::string records;  ///< empty: default_records_folder()
  bool no_record = false;
  bool no_verify = false;
};

// Now as ISO 8601 UTC, to the second.
std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

// The marked copy in memory: in the input's own format, every byte but positions (and the normals
// that follow them) kept; or, asked for another format, the marked surface as a plain mesh.
struct MarkedFiles {
  DocumentFiles files;  // the main file "" and the companions that changed
  MeshFormat format;
  bool whole = true;  // the document kept whole
};

MarkedFiles marked_files(const EmbedArgs& args, const MeshDocument& document, const WeldedSurface& surface,
                         const Mesh& marked) {
  const MeshFormat out_format = mesh_format_from_path(args.out);
  if (out_format == document.format()) {
    const MovedSlots moved = move_slots(document, surface, marked.V);
    return {document.write(moved.positions, moved.rotations, companion_names(args.in, args.out)), out_format, true};
  }
  const bool binary = out_format == MeshFormat::ply || out_format == MeshFormat::stl;
  return {{{"", write_mesh_to_memory(marked, out_format, {.binary = binary})}}, out_format, false};
}

// The copy as a reader of its bytes finds it: unchanged companions come from beside the input.
Mesh read_back_copy(const EmbedArgs& args, const MarkedFiles& marked) {
  const std::filesystem::path in_folder = std::filesystem::path(args.in).parent_path();
  return read_back(marked.files, marked.format, [&](const std::string& uri) {
    return read_file_bytes(in_folder / percent_decoded(uri), ReadOptions{}.max_file_bytes);
  });
}

struct Written {
  std::vector<std::filesystem::path> files;
  bool whole = true;
};

Written write_marked(const EmbedArgs& args, const MeshDocument& document, const MarkedFiles& marked) {
  if (marked.whole) return {write_document_files(args.in, args.out, document, marked.files), true};
  write_file_atomically(args.out, marked.files.at(""));
  return {{args.out}, false};
}

// The copy read back by the real detector before anything is written (verify_copy.hpp).
// What the copies of one run share for their self-checks: the original's registration data, and
// whether a copy of it moved by the mild attack has registered. The next copies then read their
// re-save in place (VerifyOptions::registration_proven: whether registration finds a moved copy
// depends on the shape, not the payload), as the daemon does for a model's copies.
class SelfChecks {
 public:
  // The registration data is built on another thread from the start: marking the first copy,
  // encoding it and parsing it back leave the time (557k vertices: 0.5 s).
  SelfChecks(const EmbedArgs& args, const PreparedModel& model) : model_(model) {
    if (!args.no_verify && resolve_threads(args.run.threads) > 1)
      building_ = std::async(std::launch::async, [&model] { return registration_target_of(model); });
  }
  const RegistrationTarget& target() {
    if (!target_) target_ = building_.valid() ? building_.get() : registration_target_of(model_);
    return *target_;
  }
  bool registration_proven = false;

 private:
  static std::unique_ptr<const RegistrationTarget> registration_target_of(const PreparedModel& model) {
    return std::make_unique<const RegistrationTarget>(model.outward_mesh());
  }
  const PreparedModel& model_;
  std::future<std::unique_ptr<const RegistrationTarget>> building_;
  std::unique_ptr<const RegistrationTarget> target_;
};

CopyVerification verify_marked(const EmbedArgs& args, const PreparedModel& model, const MarkedFiles& marked,
                               const Bits& payload, const WatermarkOptions& options, SelfChecks& checks,
                               const JobControl* control) {
  if (args.no_verify) return {.readings = {}, .skipped = true};
  VerifyOptions verify;
  verify.registration_proven = checks.registration_proven;
  Mesh copy = read_back_copy(args, marked);  // before waiting for the registration data: parsing is time it has
  CopyVerification v =
      verify_copy(model, checks.target(), std::move(copy), args.key, payload, options, verify, control);
  require_readable(v, payload);
  checks.registration_proven = true;
  return v;
}

// The original as prepared, beside the records: the cache's file of it linked there when there is
// one (the same bytes) rather than serialized again (557k vertices: 132 MB of memory and 0.4 s).
void store_prepared(const std::filesystem::path& file, const PreparedModel& model,
                    const std::filesystem::path& cached) {
  std::error_code unlinked;  // another filesystem, or the cache trimmed by another run meanwhile
  if (!cached.empty()) std::filesystem::create_hard_link(cached, file, unlinked);
  if (cached.empty() || unlinked) return write_file_atomically(file, serialize_prepared_model(model));
  fsync_directory(file.has_parent_path() ? file.parent_path() : std::filesystem::path("."));
}

// Writes what detection needs to read this copy (proto/copy_record.hpp): the record, and the
// original as prepared, named by the original and the grid base so that every copy of one
// original in the records folder shares them (they are as large as a few copies of the mesh).
// Returns the record's path.
std::string write_copy_record(const EmbedArgs& args, const PreparedModel& model, const std::filesystem::path& cached,
                              const WatermarkOptions& options, const Bits& payload, bool verified) {
  const std::filesystem::path records =
      args.records.empty() ? default_records_folder() : std::filesystem::path(args.records);
  std::string record_file =
      args.record.empty() ? record_path_in(records, args.out, hex_from_bits(payload)).string() : args.record;
  const std::filesystem::path record_path(record_file);
  const std::string stem = stored_original_stem(model.digest, args.scheme.base_solid());
  const CopyRecord record{hex_from_bits(payload),
                          args.scheme.scheme,
                          args.scheme.wavelet,
                          args.scheme.base,
                          options.strength_percent,
                          model.digest,
                          static_cast<long long>(model.mesh.V.rows()),
                          static_cast<long long>(model.mesh.F.rows()),
                          args.in,
                          args.out,
                          utc_now(),
                          stem + ".ply",
                          stem + ".prepared",
                          verified,
                          args.recipient};
  const std::filesystem::path folder = record_path.parent_path();
  if (!folder.empty()) std::filesystem::create_directories(folder);
  if (!std::filesystem::exists(folder / record.stored_original))
    write_file_atomically(folder / record.stored_original,
                          write_mesh_to_memory(model.mesh, MeshFormat::ply, {.binary = true}));
  if (!std::filesystem::exists(folder / record.stored_prepared))
    store_prepared(folder / record.stored_prepared, model, cached);
  write_file_atomically(record_file, to_json(record).dump(2) + "\n");
  return record_file;
}

// What an embed produced, for the report.
struct EmbedOutcome {
  const PreparedModel& model;
  const WatermarkOptions& options;
  const EmbedResult& result;
  SurfaceDistance distortion;
  CopyVerification verification;
  Written written;
  Bits payload;
  std::size_t further_instances = 0;  ///< of instanced meshes, marked with their first
  std::string record_file;            ///< empty with --no-record
  StageSeconds seconds;               ///< the stages outside embed_watermark
  std::string cache;                  ///< the prepared original: hit, miss or off
};

void print_embed_json(const EmbedArgs& args, const MeshDocument& document, const WeldedSurface& surface,
                      const EmbedOutcome& o) {
  nlohmann::json j = embed_report(o.model, o.options, o.result, o.distortion);
  j["input"] = args.in;
  j["output"] = args.out;
  j["document"] = document_json(document, surface);
  j["kept_whole"] = o.written.whole;
  j["files"] = nlohmann::json::array();
  for (const auto& f : o.written.files) j["files"].push_back(f.string());
  j["payload"] = hex_from_bits(o.payload);
  j["further_instances"] = o.further_instances;
  j["verification"] = o.verification;
  j["record"] = o.record_file.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.record_file);
  j["cache"] = o.cache;
  for (const auto& [stage, seconds] : o.seconds) j["seconds"][stage] = seconds;
  j["seconds"]["total"] = process_seconds();  // the stages above add up to it (parameterization is in prepare)
  std::cout << j.dump(2) << "\n";
}

void print_embed_text(const EmbedArgs& args, const EmbedOutcome& o) {
  const PreparedModel& model = o.model;
  const std::string carriers_on =
      model.spherical()
          ? "grid level " + std::to_string(model.level()) + " (" + std::to_string(model.sample_count()) + " samples" +
                (model.basis == MeshBasis::sphere_filled ? ", holes closed for the parameterization" : "") + ")"
          : std::to_string(model.bumps->values.cols()) + " bumps in " + std::to_string(model.bumps->bands()) + " bands";
  std::printf(
      "%s -> %s: %d-bit payload in %d carriers on %s; "
      "distortion MRMS %.4f%%, Hausdorff %.4f%% of the bbox diagonal\n",
      args.in.c_str(), args.out.c_str(), static_cast<int>(o.payload.size()), o.result.carriers, carriers_on.c_str(),
      100 * o.distortion.mrms_relative(), 100 * o.distortion.hausdorff_relative());
  for (const std::string& w : o.result.warnings) std::fprintf(stderr, "  warning: %s\n", w.c_str());
  if (o.verification.skipped) std::printf("  not verified (--no-verify): nobody has read this copy back\n");
  else
    std::printf("  verified: the payload reads back %s and %s (%.2f s)\n", o.verification.readings[0].name.c_str(),
                o.verification.readings[1].name.c_str(), o.verification.seconds());
  if (model.report.small_components)
    std::printf("  note: %zu component(s) below %zu vertices left unmarked\n", model.report.small_components,
                model.report.marked_component_floor);
  if (o.further_instances)
    std::printf("  note: %zu further instance(s) of instanced meshes carry the mark with their first\n",
                o.further_instances);
  if (!o.written.whole)
    std::printf("  note: written as a plain %s mesh: positions and triangles of the marked surface only\n",
                to_string(mesh_format_from_path(args.out)).c_str());
  for (std::size_t i = 0; i + 1 < o.written.files.size(); ++i)  // the main file comes last
    std::printf("  also wrote %s\n", o.written.files[i].string().c_str());
  if (!o.record_file.empty())
    std::printf(
        "  record of the copy: %s, with the original as prepared beside it (meshmark detect --record reads them)\n",
        o.record_file.c_str());
}

// The original read and prepared once, for every copy made of it.
struct Original {
  std::unique_ptr<MeshDocument> document;
  WeldedSurface surface;
  PreparedModel model;
  double load_seconds = 0;
  double prepare_seconds = 0;  ///< of this run: loading from the cache, or preparing
  std::string cache;           ///< hit, miss or off
  std::filesystem::path file;  ///< the cache's file of the prepared original (empty: none)
};

Original prepare_original(const EmbedArgs& args, const JobControl* control) {
  Original o;
  StageSeconds seconds;
  o.document = timed(seconds, "load", [&] { return read_document_file(args.in); });
  o.surface = timed(seconds, "load", [&] { return document_surface(*o.document); });
  o.load_seconds = seconds["load"];
  PrepareOptions prepare;
  prepare.base = args.scheme.base_solid();
  CacheUse cache;
  o.model = timed(seconds, "prepare",
                  [&] { return prepare_through_cache(o.surface.mesh, prepare, args.cache, control, cache); });
  o.prepare_seconds = seconds["prepare"];
  o.cache = args.cache.disabled ? "off" : cache.hit ? "hit" : "miss";
  o.file = cache.file;
  return o;
}

// The distortion line's MRMS and Hausdorff, measured while the copy is encoded and read back
// (on one thread beside them when there are two: the self-check leaves a core idle about half of
// its time), so "distortion" in the stage seconds is what remains to wait for. 50,000 samples a
// side: the MRMS within 0.1 % of a million samples' on the bunny and the armadillo, in a quarter
// of the time of the default 200,000. The figures do not depend on the thread count.
std::future<SurfaceDistance> measure_distortion(const EmbedArgs& args, const Mesh& original, const Mesh& copy) {
  const bool beside = resolve_threads(args.run.threads) > 1;
  return std::async(beside ? std::launch::async : std::launch::deferred, [&original, &copy, &args, beside] {
    return compare_meshes(original, copy, {.samples = 50000, .threads = beside ? 1 : args.run.threads});
  });
}

// One copy of the prepared original for args.out with args.payload: marked, read back, written,
// recorded, reported.
void embed_copy(const EmbedArgs& args, const Original& original, SelfChecks& checks) {
  check_output(args.in, args.out, *original.document);
  const Bits payload = bits_from_hex(args.payload);
  const WatermarkOptions options = args.scheme.watermark();
  std::optional<TerminalProgress> progress(std::in_place, "embed " + args.recipient, !args.run.quiet, args.run.threads);
  const EmbedResult result = embed_watermark(original.model, args.key, payload, options, progress->control());
  std::future<SurfaceDistance> measuring = measure_distortion(args, original.surface.mesh, result.mesh);
  StageSeconds seconds{{"load", original.load_seconds}, {"prepare", original.prepare_seconds}};
  if (original.cache == "hit") seconds["parameterization"] = 0;  // done by the run that cached it
  CopyVerification verification;
  Written written;
  {  // the copy's bytes are let go once written: at millions of vertices, hundreds of megabytes
    const MarkedFiles marked =
        timed(seconds, "encode", [&] { return marked_files(args, *original.document, original.surface, result.mesh); });
    verification = timed(seconds, "verify", [&] {
      return verify_marked(args, original.model, marked, payload, options, checks, progress->control());
    });
    progress.reset();
    written = timed(seconds, "write", [&] { return write_marked(args, *original.document, marked); });
  }
  const SurfaceDistance distortion = timed(seconds, "distortion", [&] { return measuring.get(); });
  std::string record = timed(seconds, "record", [&] {
    return args.no_record ? std::string()
                          : write_copy_record(args, original.model, original.file, options, payload, !args.no_verify);
  });
  EmbedOutcome outcome{original.model,
                       options,
                       result,
                       distortion,
                       std::move(verification),
                       std::move(written),
                       payload,
                       original.document->further_instances().size(),
                       std::move(record),
                       std::move(seconds),
                       original.cache};
  if (args.json) print_embed_json(args, *original.document, original.surface, outcome);
  else print_embed_text(args, outcome);
}

// A fresh payload of `bits` (16 to 64) for each recipient, none twice.
std::vector<std::string> fresh_payloads(std::size_t n, int bits) {
  std::random_device entropy;
  std::set<std::string> made;
  while (made.size() < n) {
    const std::uint64_t v = (static_cast<std::uint64_t>(entropy()) << 32) ^ entropy();
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(v));
    made.insert(std::string(hex).substr(0, static_cast<std::size_t>(bits / 4)));
  }
  std::vector<std::string> payloads(made.begin(), made.end());
  std::shuffle(payloads.begin(), payloads.end(), std::mt19937_64(entropy()));
  return payloads;
}

// "<stem>-<recipient><ext>" in the folder OUT.
std::string copy_name(const EmbedArgs& args, const std::string& recipient) {
  const std::filesystem::path in(args.in);
  return (std::filesystem::path(args.out) / file_safe(in.stem().string() + "-" + recipient + in.extension().string()))
      .string();
}

int run_embed(const EmbedArgs& args) {
  const bool batch = !args.recipients.empty() || !args.recipients_file.empty();
  if (batch == !args.payload.empty())
    throw std::invalid_argument(batch ? "--recipients assigns each copy its payload: no --payload with it"
                                      : "give --payload (or --recipients for a copy per recipient)");
  const Original original = [&] {
    const TerminalProgress progress("prepare", !args.run.quiet, args.run.threads);
    return prepare_original(args, progress.control());
  }();
  SelfChecks checks(args, original.model);
  if (!batch) {
    embed_copy(args, original, checks);
    return kExitOk;
  }
  const std::vector<std::string> names = read_recipients(args.recipients, args.recipients_file);
  // As long as the model keeps through simplification and remeshing (64 bits on most meshes).
  const CarrierField& field =
      carrier_cache(original.model).field(original.model, args.scheme.watermark().wavelet, args.run.threads);
  const int bits = assigned_payload_bits(robust_payload_bits(field, args.scheme.watermark()));
  const std::vector<std::string> payloads = fresh_payloads(names.size(), bits);
  std::filesystem::create_directories(args.out);
  for (std::size_t k = 0; k < names.size(); ++k) {
    EmbedArgs one = args;
    one.recipient = names[k];
    one.payload = payloads[k];
    one.out = copy_name(args, names[k]);
    one.record.clear();
    embed_copy(one, original, checks);
  }
  return kExitOk;
}

}  // namespace

void register_embed(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("embed", "Embed a keyed payload in a mesh");
  auto args = std::make_shared<EmbedArgs>();
  cmd->add_option("in", args->in, "Original mesh or asset (.obj, .off, .ply, .stl, .glb, .gltf, .3mf)")->required();
  cmd->add_option("out", args->out,
                  "Marked copy: the original's format keeps the asset whole; another of obj, off, ply, stl writes the "
                  "marked surface only")
      ->required();
  cmd->add_option("--key", args->key, "The owner's secret key")->required();
  cmd->add_option("--payload", args->payload, "Payload as hex digits (4 bits each), e.g. 0123456789abcdef");
  cmd->add_option("--recipients", args->recipients,
                  "A copy for each, into the folder OUT as <name>-<recipient>.<ext>, each with a fresh payload (64 "
                  "bits, or what a small model keeps) "
                  "and a record naming its recipient")
      ->delimiter(',');
  cmd->add_option("--recipients-file", args->recipients_file,
                  "Recipients listed in a file (one per line, or a CSV's first column)");
  args->scheme.add_to(cmd);
  cmd->add_flag("--json", args->json, "Print JSON");
  args->run.add_to(cmd);
  args->cache.add_to(cmd);
  cmd->add_option("--record", args->record,
                  "Where to write the copy's record (default: in the records folder, named after OUT and the "
                  "payload; the original as prepared goes beside it)");
  cmd->add_option("--records", args->records,
                  "The records folder (default: $MESHMARK_RECORDS, else ~/.local/share/meshmark/records)");
  cmd->add_flag("--no-record", args->no_record, "Write no record of the copy");
  cmd->add_flag("--no-verify", args->no_verify,
                "Hand out the copy without reading it back (as written and after a mild attack) first");
  cmd->callback([&action, args] { action = [args] { return run_embed(*args); }; });
}

}  // namespace meshmark::cli
