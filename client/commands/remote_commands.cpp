// meshmark owners|jobs|health: talking to a meshmarkd daemon (models: remote_models_commands.cpp).
//   --server URL (MESHMARK_SERVER, default http://127.0.0.1:8080), --token T (MESHMARK_TOKEN)

#include <iostream>

#include "client/commands/commands.hpp"
#include "client/commands/remote_leaf.hpp"
#include "core/util/atomic_file.hpp"
#include "proto/links.hpp"

namespace meshmark::cli {

namespace {

// A command that takes one id and answers with what `body` makes of it.
void id_leaf(CLI::App* parent, const std::string& name, const std::string& help, Action& action,
             std::function<Answer(const RemoteClient&, const Output&, const std::string& id)> body,
             const char* token_env = kOwnerToken) {
  auto id = std::make_shared<std::string>();
  remote_leaf(
      parent, name, help, action, [id](CLI::App* c) { c->add_option("id", *id)->required(); },
      [id, body = std::move(body)](const RemoteClient& client, const Output& output) {
        return body(client, output, *id);
      },
      token_env);
}

std::string key_line(const nlohmann::json& answer) {
  return "its API key, shown this once: " + answer.value("api_key", std::string("?"));
}

void register_owners(CLI::App& app, Action& action) {
  auto* owners = app.add_subcommand("owners", "Daemon: owners (needs the admin token)");
  owners->require_subcommand(1);
  auto owner_name = std::make_shared<std::string>("owner");
  remote_leaf(
      owners, "create", "Create an owner; prints its API key (shown once)", action,
      [owner_name](CLI::App* c) { c->add_option("--name", *owner_name, "Owner name (unique)"); },
      [owner_name](const RemoteClient& client, const Output&) {
        const nlohmann::json made = client.post_json(links::owners(), {{"name", *owner_name}});
        return Answer{
            "owner \"" + made.value("name", "") + "\" created (" + made.value("owner_id", "") + "); " + key_line(made),
            made};
      },
      kAdminToken);
  remote_leaf(
      owners, "list", "List the owners and whether their keys work", action, [](CLI::App*) {},
      [](const RemoteClient& client, const Output&) {
        const nlohmann::json list = client.get_json(links::owners());
        return Answer{std::to_string(list.value("owners", nlohmann::json::array()).size()) + " owner(s)", list};
      },
      kAdminToken);
  id_leaf(
      owners, "rotate-key", "Give an owner a new API key (printed once); the old one stops working", action,
      [](const RemoteClient& client, const Output&, const std::string& id) {
        const nlohmann::json rotated = client.post_json(links::owner_key(id), nlohmann::json::object());
        return Answer{"owner " + id + " has a new key and the old one no longer works; " + key_line(rotated), rotated};
      },
      kAdminToken);
  id_leaf(
      owners, "watermark-key",
      "The key an owner's copies are marked under, for meshmark embed/detect/trace --key on a workstation (a secret)",
      action,
      [](const RemoteClient& client, const Output&, const std::string& id) {
        const nlohmann::json key = client.get_json(links::owner_watermark_key(id));
        return plain("owner " + id + "'s watermark key (meshmark detect --key): " + key.value("watermark_key", ""),
                     key);
      },
      kAdminToken);
  id_leaf(
      owners, "revoke-key", "Revoke an owner's API key (until the next rotate-key)", action,
      [](const RemoteClient& client, const Output&, const std::string& id) {
        client.remove(links::owner_key(id));
        return plain("owner " + id + "'s API key is revoked", {{"owner_id", id}, {"revoked", true}});
      },
      kAdminToken);
}

Answer job_answer(const nlohmann::json& job) {
  if (!succeeded(job) && job.contains("error")) return unsuccessful(job);
  const std::string line = "job " + job.value("id", std::string("?")) + " (" + job.value("kind", std::string("?")) +
                           "): " + job.value("state", std::string("?"));
  return {line, job, succeeded(job) || !job.contains("finished_at") ? kExitOk : kExitRefused};
}

void register_jobs(CLI::App& app, Action& action) {
  auto* jobs = app.add_subcommand("jobs", "Daemon: jobs");
  jobs->require_subcommand(1);
  id_leaf(jobs, "show", "Show a job", action, [](const RemoteClient& client, const Output&, const std::string& id) {
    return job_answer(client.get_json(links::job(id)));
  });
  id_leaf(jobs, "wait", "Wait until a job finishes (exit 0 when it succeeded)", action,
          [](const RemoteClient& client, const Output& output, const std::string& id) {
            return job_answer(wait_with_progress(client, id, "job", output));
          });
  // A job's file: to --out, or to standard output when `out_default` is empty and none is given.
  auto file_leaf = [&](const char* name, const char* help, std::string (*path)(const std::string&),
                       std::string (*out_default)(const std::string&)) {
    auto job_id = std::make_shared<std::string>();
    auto out = std::make_shared<std::string>();
    remote_leaf(
        jobs, name, help, action,
        [job_id, out, out_default](CLI::App* c) {
          c->add_option("id", *job_id)->required();
          c->add_option("--out", *out,
                        out_default ? "File to write (default: " + out_default("<job id>") + ")"
                                    : std::string("File to write (default: standard output)"));
        },
        [job_id, out, path, out_default](const RemoteClient& client, const Output&) {
          const std::string bytes = client.get_bytes(path(*job_id));
          const std::string file = out->empty() && out_default ? out_default(*job_id) : *out;
          if (file.empty()) {
            std::cout << bytes;
            return Answer{};
          }
          write_file_atomically(file, bytes);
          return plain("wrote " + file + " (" + std::to_string(bytes.size()) + " bytes)",
                       {{"file", file}, {"bytes", bytes.size()}});
        });
  };
  file_leaf("result", "Download a job's result", links::job_result, nullptr);
  file_leaf("report", "Download a detection's evidence report (one self-contained HTML file)", links::job_report,
            [](const std::string& id) { return "evidence-" + id + ".html"; });
  id_leaf(jobs, "cancel", "Cancel a job", action, [](const RemoteClient& client, const Output&, const std::string& id) {
    client.remove(links::job(id));
    return plain("job " + id + ": cancel asked (a queued job ends now, a running one at its next step)",
                 {{"job_id", id}, {"cancel_requested", true}});
  });
}

}  // namespace

void register_remote(CLI::App& app, Action& action) {
  register_owners(app, action);
  register_remote_models(app, action);
  register_jobs(app, action);
  remote_leaf(
      &app, "health", "Exit 0 if the daemon answers /livez (for container health checks)", action, [](CLI::App*) {},
      [](const RemoteClient& client, const Output&) {
        if (client.alive()) return plain("the daemon answers", {{"alive", true}});
        return plain("the daemon does not answer /livez", {{"alive", false}}, kExitRefused);
      });
}

}  // namespace meshmark::cli
