// meshmark trace SUSPECT --key KEY RECORD...: which of the copies handed out (each with the
// record embed wrote beside it) a suspect is.

#include <cmath>
#include <cstdio>
#include <iostream>

#include "client/commands/commands.hpp"
#include "client/commands/verdicts.hpp"
#include "client/commands/copy_record_files.hpp"
#include "client/commands/run_options_cli.hpp"
#include "client/terminal_progress.hpp"
#include "core/io/document_surface.hpp"
#include "core/watermark/trace_copies.hpp"
#include "proto/core_json.hpp"

namespace meshmark::cli {

namespace {

struct TraceArgs {
  std::string suspect, key;
  std::vector<std::string> records;
  bool json = false;
  RunArgs run;
};

// The records, which must be copies of one original prepared on one grid base (they are read
// against that one prepared original).
std::vector<CopyRecord> read_records(const std::vector<std::string>& paths) {
  std::vector<CopyRecord> records;
  for (const std::string& path : paths) {
    records.push_back(read_copy_record(path));
    const CopyRecord& first = records.front();
    const CopyRecord& r = records.back();
    if (r.stored_original.empty())
      throw std::invalid_argument(path +
                                  ": the record stores no original beside it, which trace reads against; "
                                  "check that copy alone with detect --record and --original");
    if (r.original_digest != first.original_digest)
      throw std::invalid_argument(path + " is a copy of " + r.original_file + ", not of " + first.original_file +
                                  " like " + paths.front() + ": trace the copies of each original separately");
    if (r.base != first.base)
      throw std::invalid_argument(path + " was made on the " + r.base + " grid, " + paths.front() + " on the " +
                                  first.base + ": trace the copies of each grid separately");
  }
  return records;
}

void print_tracing(const TraceArgs& args, const std::vector<CopyRecord>& records, const Tracing& t) {
  if (args.json) {
    nlohmann::json j = t.result;
    j["suspect"] = args.suspect;
    j["readings"] = t.readings;
    j["ranked"] = nlohmann::json::array();
    for (const CopyScore& c : t.ranked)
      j["ranked"].push_back({{"record", args.records[c.copy]},
                             {"copy", records[c.copy].copy_file},
                             {"payload", records[c.copy].payload},
                             {"recipient", records[c.copy].recipient},
                             {"log10_p_value", c.log10_p_value}});
    j["match"] = t.match ? j["ranked"][0] : nlohmann::json(nullptr);
    std::cout << j.dump(2) << "\n";
    return;
  }
  if (t.match) {
    const CopyRecord& r = records[t.match->copy];
    const std::string whose =
        r.recipient.empty() ? r.copy_file + " (" : "given to " + quoted_name(r.recipient) + " (" + r.copy_file + ", ";
    std::printf("%s: the copy %srecord %s, payload %s); %s\n", args.suspect.c_str(), whose.c_str(),
                args.records[t.match->copy].c_str(), r.payload.c_str(),
                coincidence_phrase(t.match->log10_p_value).c_str());
  } else if (t.result.detected) {
    std::printf("%s: marked with this key, but none of the %zu copies given matches (p %.2g at best)\n",
                args.suspect.c_str(), records.size(),
                t.ranked.empty() ? 1.0 : std::pow(10.0, t.ranked.front().log10_p_value));
  } else {
    std::printf("%s: no watermark of this key found among the %zu copies (p %.2g)\n", args.suspect.c_str(),
                records.size(), t.result.p_value);
  }
}

int run_trace(const TraceArgs& args) {
  const std::vector<CopyRecord> records = read_records(args.records);
  std::vector<KnownCopy> copies;
  for (const CopyRecord& r : records)
    copies.push_back({bits_from_hex(r.payload), parse_scheme(r.scheme), parse_wavelet_type(r.wavelet)});
  TraceOptions options;
  options.detect.watermark.scheme = copies.front().scheme;
  options.detect.watermark.wavelet = copies.front().wavelet;
  options.detect.payload_bits = static_cast<int>(copies.front().payload.size());
  std::optional<TerminalProgress> progress(std::in_place, "trace", !args.run.quiet, args.run.threads);
  const PreparedModel model = load_recorded_original(args.records.front(), records.front(), progress->control());
  const Mesh suspect = read_surface(args.suspect);
  const Tracing tracing = trace_copies(model, suspect, args.key, copies, options, nullptr, progress->control());
  progress.reset();
  print_tracing(args, records, tracing);
  return tracing.match ? kExitOk : kExitRefused;
}

}  // namespace

void register_trace(CLI::App& app, Action& action) {
  auto* cmd =
      app.add_subcommand("trace", "Name the copy a suspect mesh is, among copies with records (of one original)");
  auto args = std::make_shared<TraceArgs>();
  cmd->add_option("suspect", args->suspect, "Suspect mesh (any triangle mesh: open, in pieces, any genus)")->required();
  cmd->add_option("records", args->records, "The copies' records (OUT.record.json, written by embed)")->required();
  cmd->add_option("--key", args->key, "The owner's secret key")->required();
  cmd->add_flag("--json", args->json, "Print JSON");
  args->run.add_to(cmd);
  cmd->callback([&action, args] { action = [args] { return run_trace(*args); }; });
}

}  // namespace meshmark::cli
