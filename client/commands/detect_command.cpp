// meshmark detect SUSPECT --original ORIG --key KEY [--bits N] [--expect HEX] [scheme options] [--json]

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

#include "client/commands/commands.hpp"
#include "client/commands/verdicts.hpp"
#include "client/commands/copy_record_files.hpp"
#include "client/commands/watermark_options_cli.hpp"
#include "client/commands/prepared_cache.hpp"
#include "client/commands/stored_originals.hpp"
#include "client/commands/run_options_cli.hpp"
#include "client/commands/stage_seconds.hpp"
#include "client/terminal_progress.hpp"
#include "core/io/document_surface.hpp"
#include "core/io/mesh_document.hpp"
#include "core/io/read_mesh.hpp"
#include "core/mesh/mesh_digest.hpp"
#include "core/registration/same_surface.hpp"
#include "core/watermark/prepared_model_io.hpp"
#include "core/watermark/combine_evidence.hpp"
#include "core/watermark/detect_lengths.hpp"
#include "core/watermark/watermark.hpp"
#include "proto/copy_record.hpp"
#include "proto/core_json.hpp"

namespace meshmark::cli {

namespace {

struct OriginalCheck {
  bool same_geometry = true;
  std::string note;                  ///< empty when the given original is byte for byte the recorded one
  std::string stored_original = {};  ///< the records folder's original read against instead, if any
};

std::string mrms_figure(double mrms) {
  char figure[32];
  std::snprintf(figure, sizeof figure, "%.1e", mrms);
  return figure;
}

// The original given beside a record that stores its own: the same surface (perhaps re-saved with
// fewer digits, reordered, moved), or another one.
OriginalCheck check_given_original(const Mesh& given, const std::string& name, const PreparedModel& recorded,
                                   const JobControl* control) {
  if (mesh_digest(given) == recorded.digest) return {};
  const SurfaceMatch match = match_surface(given, RegistrationTarget(recorded.outward_mesh()), control);
  const std::string figure = mrms_figure(match.mrms_relative);
  if (match.same)
    return {true, name + " is the recorded original re-saved, reordered or moved (MRMS " + figure +
                      " of the diagonal after alignment); the copy is read against the recorded original"};
  return {false, name + " is not the original the record names (MRMS " + figure +
                     " of the diagonal after alignment); the copy is read against the recorded original"};
}

// One line a non-expert can act on: what was found, and how likely that is by coincidence.
std::string plain_verdict(const DetectResult& r) {
  if (r.detected)
    return "marked with this key" + (r.payload ? ", payload " + hex_from_bits(*r.payload) : std::string()) + "; " +
           coincidence_phrase(r.log10_p_value);
  return nothing_found_phrase(r.p_value, r.log10_p_value);
}

struct DetectArgs {
  std::string suspect, original, key, expect, record, records;
  int bits = 64;
  bool bits_given = false;
  SchemeArgs scheme;
  bool json = false;
  RunArgs run;
  CacheArgs cache;
};

// Settings from the copy's record; an option given that contradicts it is refused.
CopyRecord apply_record(DetectArgs& args) {
  CopyRecord record = read_copy_record(args.record);
  args.scheme.fill_from_record(record.scheme, record.wavelet, record.base);
  const int recorded_bits = static_cast<int>(4 * record.payload.size());
  if (args.bits_given && args.bits != recorded_bits)
    throw std::invalid_argument("--bits " + std::to_string(args.bits) + " contradicts the copy's record (" +
                                std::to_string(recorded_bits) + ")");
  if (!args.expect.empty() && hex_from_bits(bits_from_hex(args.expect)) != record.payload)
    throw std::invalid_argument("--expect " + args.expect + " contradicts the copy's record (" + record.payload + ")");
  args.bits = recorded_bits;
  args.expect = record.payload;
  return record;
}

DetectOptions detect_options(const DetectArgs& args) {
  DetectOptions options;
  options.watermark = args.scheme.watermark();
  options.payload_bits = args.bits;
  if (!args.expect.empty()) {
    options.expected = bits_from_hex(args.expect);
    if (args.bits == 64 && static_cast<int>(options.expected->size()) != 64)
      options.payload_bits = static_cast<int>(options.expected->size());
  }
  return options;
}

bool record_stores_original(const std::optional<CopyRecord>& record) {
  return record && !record->stored_original.empty();
}

// The original to read against: the record's stored one (checked against --original if given),
// else --original prepared now (checked against the digest the record names).
PreparedModel original_to_read(const DetectArgs& args, const std::optional<CopyRecord>& record,
                               const std::optional<Mesh>& given, OriginalCheck& check, const JobControl* control) {
  if (record_stores_original(record)) {
    PreparedModel model = load_recorded_original(args.record, *record, control);
    if (given) check = check_given_original(*given, args.original, model, control);
    return model;
  }
  if (!given) throw std::invalid_argument("give --original (or a --record that stores the original)");
  PrepareOptions prepare;
  prepare.base = args.scheme.base_solid();
  CacheUse cache;
  PreparedModel model = prepare_through_cache(*given, prepare, args.cache, control, cache);
  if (record && record->original_digest != model.digest)
    check = {false,
             args.original + " is not the original the record names (" + record->original_file + ", " +
                 std::to_string(record->original_vertices) +
                 " vertices): its geometry differs (re-saved with "
                 "fewer digits, reordered, moved or edited?), and the copy reads only against the original itself"};
  return model;
}

// Without a record, --bits or --expect, every length a copy of this original could carry is read.
DetectResult read_against(const DetectArgs& args, bool recorded, const DetectOptions& options,
                          const PreparedModel& model, const Mesh& suspect, const JobControl* control) {
  const std::vector<int> lengths = recorded || args.bits_given || !args.expect.empty()
                                       ? std::vector<int>{options.payload_bits}
                                       : plausible_payload_lengths(model, options.watermark, threads_of(control));
  return detect_at_lengths(model, suspect, args.key, lengths, options, nullptr, control);
}

struct Reading {
  DetectResult result;
  OriginalCheck check;
};

// Without a record that stores the original, --original may be a master re-exported since the
// copy was made: the copy is read against each stored original it is the surface of
// (stored_originals.hpp) until one finds the mark. `originals` counts those that may be read,
// --original itself after them: each reading's p-value is charged for all of them.
std::optional<Reading> read_against_stored(const DetectArgs& args, const Mesh& given, const Mesh& suspect,
                                           const DetectOptions& options, StageSeconds& seconds, int& originals,
                                           const JobControl* control) {
  const std::filesystem::path folder =
      args.records.empty() ? default_records_folder() : std::filesystem::path(args.records);
  const std::vector<FoundOriginal> found = timed(seconds, "stored originals", [&] {
    return find_stored_originals(given, stored_originals_in(folder, args.scheme.base_solid()), control);
  });
  originals = static_cast<int>(found.size()) + 1;
  for (const FoundOriginal& f : found) {
    DetectResult result = read_against(args, false, options, f.model, suspect, control);
    charge_for_readings(result, originals, options.false_alarm);
    if (result.detected)
      return Reading{std::move(result),
                     {true,
                      args.original + " is the original stored as " + f.mesh_file.string() +
                          ", re-saved, reordered or moved (MRMS " + mrms_figure(f.mrms_relative) +
                          " of the diagonal after alignment); the copy is read against it as it was prepared",
                      f.mesh_file.string()}};
  }
  return std::nullopt;
}

void print_detection(const DetectArgs& args, const DetectResult& result, bool recorded, const OriginalCheck& check,
                     const StageSeconds& seconds) {
  if (args.json) {
    nlohmann::json j = result;
    for (const auto& [stage, s] : seconds) j["seconds"][stage] = s;
    j["seconds"]["total"] = process_seconds();  // the stages above add up to it
    j["suspect"] = args.suspect;
    j["original"] = args.original;
    if (recorded)
      j["record"] = {{"file", args.record},
                     {"original_matches", check.same_geometry},
                     {"note", check.note.empty() ? nlohmann::json(nullptr) : nlohmann::json(check.note)}};
    if (!check.stored_original.empty()) j["stored_original"] = {{"file", check.stored_original}, {"note", check.note}};
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::printf("%s: %s\n%s", args.suspect.c_str(), plain_verdict(result).c_str(),
              remote_evidence(nlohmann::json(result)).c_str());
}

Reading read_suspect(const DetectArgs& args, const std::optional<CopyRecord>& record, const DetectOptions& options,
                     StageSeconds& seconds, const JobControl* control) {
  const Mesh suspect = timed(seconds, "suspect", [&] { return read_surface(args.suspect); });
  std::optional<Mesh> given;
  if (!args.original.empty()) given = timed(seconds, "given original", [&] { return read_surface(args.original); });
  int originals = 1;
  if (given && !record_stores_original(record))
    if (std::optional<Reading> stored =
            read_against_stored(args, *given, suspect, options, seconds, originals, control))
      return std::move(*stored);
  Reading reading;
  const PreparedModel model =
      timed(seconds, "original", [&] { return original_to_read(args, record, given, reading.check, control); });
  reading.result = read_against(args, record.has_value(), options, model, suspect, control);
  charge_for_readings(reading.result, originals, options.false_alarm);
  return reading;
}

int run_detect(DetectArgs& args) {
  std::optional<CopyRecord> record;
  if (!args.record.empty()) record = apply_record(args);
  const DetectOptions options = detect_options(args);
  std::optional<TerminalProgress> progress(std::in_place, "detect", !args.run.quiet, args.run.threads);
  StageSeconds seconds;
  const Reading reading = read_suspect(args, record, options, seconds, progress->control());
  progress.reset();
  if (!reading.check.note.empty() && !args.json)
    std::fprintf(stderr, "meshmark: %s%s\n",
                 reading.check.same_geometry ? "" : "warning: ", reading.check.note.c_str());
  print_detection(args, reading.result, record.has_value(), reading.check, seconds);
  return reading.result.detected ? kExitOk : kExitRefused;
}

}  // namespace

void register_detect(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("detect", "Detect and read a payload in a suspect mesh, against its original");
  auto args = std::make_shared<DetectArgs>();
  cmd->add_option("suspect", args->suspect, "Suspect mesh (any triangle mesh: open, in pieces, any genus)")->required();
  cmd->add_option("--original", args->original,
                  "The original (unmarked) mesh; optional with a --record that stores it (then checked against it)");
  cmd->add_option("--key", args->key, "The owner's secret key")->required();
  CLI::Option* bits_option = cmd->add_option("--bits", args->bits, "Payload length in bits")->capture_default_str();
  cmd->add_option("--expect", args->expect, "Expected payload (hex): reports the bit error rate");
  args->scheme.add_to(cmd);
  cmd->add_option(
      "--record", args->record,
      "The copy's record (written by embed beside the copy): its settings and payload, and which original it names");
  cmd->add_flag("--json", args->json, "Print JSON");
  args->run.add_to(cmd);
  cmd->add_option("--records", args->records,
                  "Where embed keeps its records and originals (default: $MESHMARK_RECORDS, else "
                  "~/.local/share/meshmark/records): an --original re-saved, reordered or moved since is read "
                  "as the stored original it is");
  args->cache.add_to(cmd);
  cmd->callback([&action, args, bits_option] {
    args->bits_given = bits_option->count() > 0;
    action = [args] { return run_detect(*args); };
  });
}

}  // namespace meshmark::cli
