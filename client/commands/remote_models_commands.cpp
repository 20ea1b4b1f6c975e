// meshmark models …: a daemon's models, the copies made of them, and suspects checked against them.

#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <sstream>
#include <vector>

#include "client/commands/recipients.hpp"
#include "client/commands/remote_leaf.hpp"
#include "client/commands/upload_package.hpp"
#include "client/commands/verdicts.hpp"
#include "core/io/mesh_document.hpp"
#include "core/util/atomic_file.hpp"
#include "proto/json_text.hpp"
#include "proto/links.hpp"
#include "proto/states.hpp"

namespace meshmark::cli {

namespace {

// The request's path with the format of the file sent and, for an upload, its name.
std::string with_format(const std::string& path, const UploadPackage& package) {
  return path + (path.find('?') == std::string::npos ? "?" : "&") + "format=" + to_string(package.format);
}

UploadPackage packaged(const std::string& file) {
  UploadPackage package = package_for_upload(file);
  warn_missing_companions(file, package);
  return package;
}

struct UploadArgs {
  std::string file, name;
  bool wait = false;
};

std::string model_line(const nlohmann::json& model) {
  std::string line = "model " + model.value("id", std::string("?")) + " " + quoted_name(model.value("name", "")) +
                     ": " + model.value("state", std::string("?")) + ", " + std::to_string(model.value("vertices", 0)) +
                     " vertices";
  if (const auto& error = model.value("error", nlohmann::json()); error.is_string())
    line += " (" + error.get<std::string>() + ")";
  return line;
}

Answer upload_model(const RemoteClient& client, const UploadArgs& args, const Output& output) {
  const UploadPackage package = packaged(args.file);
  const std::string name = args.name.empty() ? std::filesystem::path(args.file).stem().string() : args.name;
  nlohmann::json model =
      client.post_file(with_format(links::models() + "?name=" + encode_query_value(name), package), package.bytes);
  if (args.wait) {
    const nlohmann::json job = wait_with_progress(client, model["job_id"], "prepare", output);
    model = client.get_json(links::model(model["id"].get<std::string>()));
    if (!succeeded(job)) model["job"] = job;
  }
  if (!package.packed.empty()) model["packed_with"] = package.packed;
  const bool failed = model.value("state", "") == to_string(ModelState::failed);
  return {model_line(model), model, failed ? kExitRefused : kExitOk};
}

struct RemoteEmbedArgs {
  std::string id, payload, recipient, requested_by, out, format, recipients_file;
  std::vector<std::string> recipients;
  double strength = std::numeric_limits<double>::quiet_NaN();  // NaN: not given (the daemon's default)
};

// The copy's format: --format, else the --out file's extension, else (empty) the model's own.
std::string copy_format(const RemoteEmbedArgs& args) {
  std::string format = args.format;
  if (!args.out.empty() && std::filesystem::path(args.out).extension() != ".zip") {  // a ZIP: the model's own
    const std::string from_out = to_string(mesh_format_from_path(args.out));         // throws for an unknown extension
    if (!format.empty() && format != from_out)
      throw std::invalid_argument("--format " + format + " contradicts --out " + args.out + " (" + from_out + ")");
    format = from_out;
  }
  return format;
}

// "<model name>-<recipient>.<format>" (the payload when there is no recipient), safe as a file name.
std::string default_copy_name(const std::string& model_name, const nlohmann::json& result) {
  std::string who = result.value("recipient", std::string());
  if (who.empty()) who = result.value("payload", std::string("copy"));
  return file_safe((model_name.empty() ? std::string("model") : model_name) + "-" + who + "." +
                   result.value("format", std::string("ply")) + (result.value("zipped", false) ? ".zip" : ""));
}

// What every copy asked for shares: its strength and who asked.
nlohmann::json shared_settings(const RemoteEmbedArgs& args) {
  nlohmann::json body = nlohmann::json::object();
  if (!std::isnan(args.strength)) body["strength"] = args.strength;  // the daemon validates it
  if (!args.requested_by.empty()) body["requested_by"] = args.requested_by;
  return body;
}

Answer embed_copy(const RemoteClient& client, const RemoteEmbedArgs& args, const Output& output) {
  nlohmann::json body = shared_settings(args);
  if (!args.payload.empty()) body["payload"] = args.payload;
  if (!args.recipient.empty()) body["recipient"] = args.recipient;
  if (const std::string format = copy_format(args); !format.empty()) body["format"] = format;
  const nlohmann::json accepted = client.post_json(links::model_embed(args.id), body);
  const nlohmann::json job = wait_with_progress(client, accepted["job_id"], "embed", output);
  if (!succeeded(job)) return unsuccessful(job);
  const std::string job_id = job["id"];
  nlohmann::json summary = job["result"];
  const std::string out = args.out.empty()
                              ? default_copy_name(client.get_json(links::model(args.id)).value("name", ""), summary)
                              : args.out;
  write_file_atomically(out, client.get_bytes(links::job_result(job_id)));
  summary["job_id"] = job_id;
  summary["file"] = out;
  const std::string who = summary.value("recipient", "").empty() ? "" : " for " + quoted_name(summary["recipient"]);
  return {"wrote " + out + ": the copy" + who + " (payload " + summary.value("payload", "") +
              "), read back before it was handed out",
          summary};
}

// One copy per recipient, asked in batches the queue can hold, each downloaded into --out (a folder).
Answer embed_batch(const RemoteClient& client, const RemoteEmbedArgs& args, const Output& output) {
  const std::vector<std::string> names = read_recipients(args.recipients, args.recipients_file);
  const std::filesystem::path folder = args.out.empty() ? std::filesystem::path(".") : std::filesystem::path(args.out);
  std::filesystem::create_directories(folder);
  const std::string model_name = client.get_json(links::model(args.id)).value("name", "");
  nlohmann::json body = shared_settings(args);
  if (!args.format.empty()) body["format"] = args.format;
  nlohmann::json made = nlohmann::json::array();
  int failed = 0;
  constexpr std::size_t kPerRequest = 16;  // well inside an owner's share of the daemon's queue
  for (std::size_t first = 0; first < names.size(); first += kPerRequest) {
    body["recipients"] = std::vector<std::string>(
        names.begin() + static_cast<std::ptrdiff_t>(first),
        names.begin() + static_cast<std::ptrdiff_t>(std::min(first + kPerRequest, names.size())));
    const nlohmann::json batch = client.post_json(links::model_embed(args.id), body);
    for (const nlohmann::json& accepted : batch.at("copies")) {
      const nlohmann::json job =
          wait_with_progress(client, accepted["job_id"],
                             "copy " + std::to_string(made.size() + 1) + " of " + std::to_string(names.size()), output);
      nlohmann::json summary = succeeded(job) ? job["result"] : nlohmann::json{{"recipient", accepted["recipient"]}};
      summary["job_id"] = job["id"];
      if (succeeded(job)) {
        const auto file = folder / default_copy_name(model_name, summary);
        write_file_atomically(file, client.get_bytes(links::job_result(job["id"])));
        summary["file"] = file.string();
      } else {
        summary["error"] = job.value("error", std::string("the job ") + job.value("state", std::string("ended")));
        ++failed;
      }
      made.push_back(summary);
    }
  }
  const std::string line = "wrote " + std::to_string(made.size() - static_cast<std::size_t>(failed)) + " of " +
                           std::to_string(names.size()) + " copies into " + folder.string() +
                           ", each read back before it was handed out" +
                           (failed ? "; " + std::to_string(failed) + " failed" : std::string());
  std::string each;  // one line per copy: where it went, or why it failed
  for (const nlohmann::json& c : made)
    each +=
        "  " + c.value("recipient", std::string()) + ": " +
        (c.contains("file") ? c.value("file", std::string()) + " (payload " + c.value("payload", std::string()) + ")"
                            : "failed: " + c.value("error", std::string())) +
        "\n";
  return {line, {{"copies", made}}, failed ? kExitRefused : kExitOk, each};
}

Answer detect_suspect(const RemoteClient& client, const std::string& model_id, const std::string& suspect,
                      const Output& output) {
  const UploadPackage package = packaged(suspect);
  const nlohmann::json accepted = client.post_file(with_format(links::model_detect(model_id), package), package.bytes);
  const nlohmann::json job = wait_with_progress(client, accepted["job_id"], "detect", output);
  if (!succeeded(job)) return unsuccessful(job);
  const nlohmann::json& result = job["result"];
  const bool found = result.value("detected", false);
  return {suspect + ": " + remote_verdict(result), job, found ? kExitOk : kExitRefused, remote_evidence(result)};
}

void register_upload(CLI::App* models, Action& action) {
  auto upload = std::make_shared<UploadArgs>();
  remote_leaf(
      models, "upload", "Upload an original (a glTF or OBJ is sent with the files it refers to, or give a .zip)",
      action,
      [upload](CLI::App* c) {
        c->add_option("file", upload->file, "Mesh file, or a ZIP of one with its companion files")->required();
        c->add_option("--name", upload->name, "Model name (default: the file name)");
        c->add_flag("--wait", upload->wait, "Wait until the model is prepared");
      },
      [upload](const RemoteClient& client, const Output& output) { return upload_model(client, *upload, output); });
}

void register_embed(CLI::App* models, Action& action) {
  auto embed = std::make_shared<RemoteEmbedArgs>();
  remote_leaf(
      models, "embed", "Make a watermarked copy for a recipient and download it", action,
      [embed](CLI::App* c) {
        c->add_option("id", embed->id, "Model id")->required();
        c->add_option("--payload", embed->payload, "Payload (hex)");
        c->add_option("--recipient", embed->recipient, "Who receives the copy (assigns a payload if none is given)");
        c->add_option(
            "--requested-by", embed->requested_by,
            "Who asked for the copy (kept with its record, shown in the copies table and the evidence report)");
        c->add_option("--strength", embed->strength, "Distortion budget (percent of the bbox diagonal)");
        c->add_option("--format", embed->format, "Format of the copy (default: the model's)");
        c->add_option("--out", embed->out,
                      "Where to write the copy (default: <model name>-<recipient>.<format>); with --recipients, "
                      "the folder for all of them");
        c->add_option("--recipients", embed->recipients, "One copy for each of these recipients")->delimiter(',');
        c->add_option("--recipients-file", embed->recipients_file,
                      "One copy for each recipient listed (one per line, or a CSV's first column)");
      },
      [embed](const RemoteClient& client, const Output& output) {
        if (embed->recipients.empty() && embed->recipients_file.empty()) return embed_copy(client, *embed, output);
        if (!embed->payload.empty() || !embed->recipient.empty())
          throw std::invalid_argument(
              "--recipients and --recipients-file assign each copy its payload: no --payload or "
              "--recipient with them");
        return embed_batch(client, *embed, output);
      });
}

// The strongest of the short-listed models' detections: one that names a copy, else one that
// found a mark, the smallest p-value first; null when none found anything.
const nlohmann::json* strongest(const std::vector<nlohmann::json>& jobs) {
  const nlohmann::json* best = nullptr;
  const auto rank = [](const nlohmann::json& job) {
    const nlohmann::json& r = job["result"];
    const bool named = r.value("match", nlohmann::json()).is_object();
    return std::pair(named ? 0 : 1, named ? r["match"].value("log10_p_value", 0.0) : r.value("log10_p_value", 0.0));
  };
  for (const nlohmann::json& job : jobs)
    if (succeeded(job) && job["result"].value("detected", false) && (!best || rank(job) < rank(*best))) best = &job;
  return best;
}

Answer search_library(const RemoteClient& client, const std::string& suspect, int candidates, const Output& output) {
  const UploadPackage package = packaged(suspect);
  const std::string path = links::library_detect() + "?candidates=" + std::to_string(candidates);
  const nlohmann::json accepted = client.post_file(with_format(path, package), package.bytes);
  nlohmann::json details = {{"models_compared", accepted["models_compared"]}, {"candidates", nlohmann::json::array()}};
  std::vector<nlohmann::json> jobs;
  for (const nlohmann::json& c : accepted["candidates"]) {
    const std::string what =
        "search: model " + std::to_string(jobs.size() + 1) + " of " + std::to_string(accepted["candidates"].size());
    jobs.push_back(wait_with_progress(client, c["job_id"], what, output));
    nlohmann::json checked = c;
    checked["state"] = jobs.back()["state"];
    if (succeeded(jobs.back())) checked["result"] = jobs.back()["result"];
    details["candidates"].push_back(checked);
  }
  const std::string compared = "the " + std::to_string(jobs.size()) + " closest in shape of your " +
                               accepted["models_compared"].dump() + " models";
  const nlohmann::json* best = strongest(jobs);
  if (!best) return {suspect + ": no watermark of this key found in " + compared, details, kExitRefused};
  const nlohmann::json& model = accepted["candidates"][static_cast<std::size_t>(best - jobs.data())];
  return {suspect + ": a copy of model " + quoted_name(model.value("model_name", "")) + " (" +
              model.value("model_id", "") + "): " + remote_verdict((*best)["result"]),
          details, kExitOk, remote_evidence((*best)["result"]) + "  searched " + compared + "\n"};
}

struct RemoteDetectArgs {
  std::vector<std::string> args;  // [model id] suspect
  int candidates = 3;
};

void register_detect(CLI::App* models, Action& action) {
  auto detect = std::make_shared<RemoteDetectArgs>();
  remote_leaf(
      models, "detect",
      "Check a suspect mesh against a model, or (no model id) search your whole library for it: whose copy is "
      "it? (exit 0 marked, 1 not)",
      action,
      [detect](CLI::App* c) {
        c->add_option("args", detect->args, "[MODEL_ID] SUSPECT (a glTF or OBJ with its files, or a .zip)")
            ->required()
            ->expected(1, 2);
        c->add_option("--candidates", detect->candidates, "Without a model: how many of the closest shapes to check")
            ->check(CLI::Range(1, 10))
            ->capture_default_str();
      },
      [detect](const RemoteClient& client, const Output& output) {
        if (detect->args.size() == 1) return search_library(client, detect->args[0], detect->candidates, output);
        return detect_suspect(client, detect->args[0], detect->args[1], output);
      });
}

// A command that takes one id and GETs what `path` names for it, answered by `line`.
void show_leaf(CLI::App* parent, const std::string& name, const std::string& help, Action& action,
               std::function<std::string(const std::string&)> path,
               std::function<std::string(const nlohmann::json&, const std::string& id)> line) {
  auto id = std::make_shared<std::string>();
  remote_leaf(
      parent, name, help, action, [id](CLI::App* c) { c->add_option("id", *id)->required(); },
      [id, path = std::move(path), line = std::move(line)](const RemoteClient& client, const Output&) {
        const nlohmann::json shown = client.get_json(path(*id));
        return Answer{line(shown, *id), shown};
      });
}

struct ExportArgs {
  bool csv = false;
  std::string out;
};

Answer export_copies(const RemoteClient& client, const ExportArgs& args) {
  const nlohmann::json list = client.get_json(links::embeddings_export());
  const std::size_t count = list.value("embeddings", nlohmann::json::array()).size();
  if (args.out.empty() && !args.csv) return {std::to_string(count) + " copies handed out across your models", list};
  const std::string bytes = args.csv ? client.get_bytes(links::embeddings_export() + "?format=csv") : list.dump(2);
  if (args.out.empty()) {
    std::cout << bytes;
    return {};
  }
  write_file_atomically(args.out, bytes);
  return plain("wrote " + args.out + ": " + std::to_string(count) + " copies handed out across your models",
               {{"file", args.out}, {"copies", count}});
}

struct CopiesArgs {
  std::string id, out;
  std::vector<std::string> recipients;
};

Answer download_copies(const RemoteClient& client, const CopiesArgs& args) {
  std::string query;
  for (const std::string& r : args.recipients)
    query += (query.empty() ? "?" : "&") + ("recipient=" + encode_query_value(r));
  const std::string bytes = client.get_bytes(links::model_copies_zip(args.id) + query);
  const std::string out = args.out.empty() ? args.id + "-copies.zip" : args.out;
  write_file_atomically(out, bytes);
  return plain(
      "wrote " + out + ": the copies of model " + args.id + " in one ZIP (" + std::to_string(bytes.size()) + " bytes)",
      {{"file", out}, {"bytes", bytes.size()}});
}

// The records that outlast a hand-out: the export of every copy, a model's detections, its copies.
void register_records(CLI::App* models, Action& action) {
  auto copies = std::make_shared<CopiesArgs>();
  remote_leaf(
      models, "copies", "Download a model's copies handed out, all or those of some recipients, as one ZIP", action,
      [copies](CLI::App* c) {
        c->add_option("id", copies->id, "Model id")->required();
        c->add_option("--recipients", copies->recipients, "Only these recipients' copies")->delimiter(',');
        c->add_option("--out", copies->out, "The ZIP to write (default: <model id>-copies.zip)");
      },
      [copies](const RemoteClient& client, const Output&) { return download_copies(client, *copies); });
  auto args = std::make_shared<ExportArgs>();
  remote_leaf(
      models, "export", "Every copy you handed out, across your models (who, what, when, settings)", action,
      [args](CLI::App* c) {
        c->add_flag("--csv", args->csv, "As CSV (one row per copy) instead of JSON");
        c->add_option("--out", args->out, "File to write");
      },
      [args](const RemoteClient& client, const Output&) { return export_copies(client, *args); });
  show_leaf(models, "detections", "The suspects checked against a model, oldest first, and what each named", action,
            links::model_detections, [](const nlohmann::json& list, const std::string& id) {
              return std::to_string(list.value("detections", nlohmann::json::array()).size()) +
                     " detection(s) against model " + id;
            });
}

}  // namespace

void register_remote_models(CLI::App& app, Action& action) {
  auto* models = app.add_subcommand("models", "Daemon: your models (originals), copies and checks");
  models->require_subcommand(1);
  register_upload(models, action);
  remote_leaf(
      models, "list", "List your models", action, [](CLI::App*) {},
      [](const RemoteClient& client, const Output&) {
        const nlohmann::json list = client.get_json(links::models());
        return Answer{std::to_string(list.value("models", nlohmann::json::array()).size()) + " model(s)", list};
      });
  show_leaf(models, "show", "Show a model", action, links::model,
            [](const nlohmann::json& model, const std::string&) { return model_line(model); });
  show_leaf(models, "embeddings", "The copies handed out", action, links::model_embeddings,
            [](const nlohmann::json& list, const std::string& id) {
              return std::to_string(list.value("embeddings", nlohmann::json::array()).size()) +
                     " copies handed out of model " + id;
            });
  auto doomed = std::make_shared<std::pair<std::string, bool>>();  // model id, --force
  remote_leaf(
      models, "delete", "Delete a model (refused while copies of it were handed out, unless --force)", action,
      [doomed](CLI::App* c) {
        c->add_option("id", doomed->first)->required();
        c->add_flag("--force", doomed->second, "Delete it although its copies can then never be traced");
      },
      [doomed](const RemoteClient& client, const Output&) {
        const auto& [id, force] = *doomed;
        client.remove(links::model(id) + (force ? "?confirm=" + encode_query_value(id) : ""));
        return plain("model " + id + " deleted", {{"model_id", id}, {"deleted", true}});
      });
  register_embed(models, action);
  register_detect(models, action);
  register_records(models, action);
}

}  // namespace meshmark::cli
