// meshmark owners|models|jobs|health: talking to a meshmarkd daemon.
//   --server URL (MESHMARK_SERVER, default http://127.0.0.1:8080), --token T (MESHMARK_TOKEN)

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>

#include "client/commands/commands.hpp"
#include "client/remote_client.hpp"
#include "core/io/mesh_format.hpp"
#include "core/util/atomic_file.hpp"

namespace meshmark::cli {

namespace {

struct Connection {
  std::string server = "http://127.0.0.1:8080";
  std::string token;
};

void add_connection(CLI::App* cmd, Connection& c, const char* token_env = "MESHMARK_TOKEN") {
  cmd->add_option("--server", c.server, "Daemon URL")->envname("MESHMARK_SERVER")->capture_default_str();
  cmd->add_option("--token", c.token, std::string("API key (or $") + token_env + ")")->envname(token_env);
}

void print(const nlohmann::json& j) { std::cout << j.dump(2) << "\n"; }

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open the file for reading");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Registers a leaf command whose action runs `body` with a client; RemoteError → exit 2.
void leaf(CLI::App* parent, const std::string& name, const std::string& help, Action& action,
          const std::function<void(CLI::App*)>& options, const std::function<int(const RemoteClient&)>& body,
          const char* token_env = "MESHMARK_TOKEN") {
  auto* cmd = parent->add_subcommand(name, help);
  auto connection = std::make_shared<Connection>();
  add_connection(cmd, *connection, token_env);
  options(cmd);
  cmd->callback([&action, connection, body] {
    action = [connection, body] {
      try {
        return body(RemoteClient(connection->server, connection->token));
      } catch (const RemoteError& e) {
        std::fprintf(stderr, "meshmark: %s\n", e.what());
        return kExitError;
      }
    };
  });
}

int finish_job(const nlohmann::json& job) {
  print(job);
  return job.value("state", "") == "succeeded" ? kExitOk : kExitRefused;
}

}  // namespace

void register_remote(CLI::App& app, Action& action) {
  auto* owners = app.add_subcommand("owners", "Daemon: owners (needs the admin token)");
  owners->require_subcommand(1);
  auto owner_name = std::make_shared<std::string>("owner");
  leaf(owners, "create", "Create an owner; prints its API key (shown once)", action,
       [owner_name](CLI::App* c) { c->add_option("--name", *owner_name, "Owner name"); },
       [owner_name](const RemoteClient& client) {
         print(client.post_json("/v1/owners", {{"name", *owner_name}}));
         return kExitOk;
       },
       "MESHMARK_ADMIN_TOKEN");
  leaf(owners, "list", "List the owners and whether their keys work", action, [](CLI::App*) {},
       [](const RemoteClient& client) {
         print(client.get_json("/v1/owners"));
         return kExitOk;
       },
       "MESHMARK_ADMIN_TOKEN");
  auto owner_id = std::make_shared<std::string>();
  leaf(owners, "rotate-key", "Give an owner a new API key (printed once); the old one stops working", action,
       [owner_id](CLI::App* c) { c->add_option("id", *owner_id, "Owner id")->required(); },
       [owner_id](const RemoteClient& client) {
         print(client.post_json("/v1/owners/" + *owner_id + "/key", nlohmann::json::object()));
         return kExitOk;
       },
       "MESHMARK_ADMIN_TOKEN");
  leaf(owners, "revoke-key", "Revoke an owner's API key (until the next rotate-key)", action,
       [owner_id](CLI::App* c) { c->add_option("id", *owner_id, "Owner id")->required(); },
       [owner_id](const RemoteClient& client) {
         client.remove("/v1/owners/" + *owner_id + "/key");
         return kExitOk;
       },
       "MESHMARK_ADMIN_TOKEN");

  auto* models = app.add_subcommand("models", "Daemon: your models (originals), copies and checks");
  models->require_subcommand(1);
  struct Upload {
    std::string file, name;
    bool wait = false;
  };
  auto upload = std::make_shared<Upload>();
  leaf(models, "upload", "Upload an original mesh", action,
       [upload](CLI::App* c) {
         c->add_option("file", upload->file, "Mesh file")->required();
         c->add_option("--name", upload->name, "Model name (default: the file name)");
         c->add_flag("--wait", upload->wait, "Wait until the model is prepared");
       },
       [upload](const RemoteClient& client) {
         const std::string format = to_string(mesh_format_from_path(upload->file));
         const std::string name = upload->name.empty() ? std::filesystem::path(upload->file).stem().string() : upload->name;
         nlohmann::json model = client.post_file("/v1/models?format=" + format + "&name=" + encode_query_value(name), read_file(upload->file));
         if (upload->wait) {
           const nlohmann::json job = client.wait_job(model["job_id"]);
           model = client.get_json("/v1/models/" + model["id"].get<std::string>());
           if (job["state"] != "succeeded") model["job"] = job;
         }
         print(model);
         return model.value("state", "") == "failed" ? kExitRefused : kExitOk;
       });
  leaf(models, "list", "List your models", action, [](CLI::App*) {},
       [](const RemoteClient& client) {
         print(client.get_json("/v1/models"));
         return kExitOk;
       });
  auto model_id = std::make_shared<std::string>();
  leaf(models, "show", "Show a model", action, [model_id](CLI::App* c) { c->add_option("id", *model_id)->required(); },
       [model_id](const RemoteClient& client) {
         print(client.get_json("/v1/models/" + *model_id));
         return kExitOk;
       });
  leaf(models, "embeddings", "The copies handed out", action,
       [model_id](CLI::App* c) { c->add_option("id", *model_id)->required(); },
       [model_id](const RemoteClient& client) {
         print(client.get_json("/v1/models/" + *model_id + "/embeddings"));
         return kExitOk;
       });
  leaf(models, "delete", "Delete a model", action, [model_id](CLI::App* c) { c->add_option("id", *model_id)->required(); },
       [model_id](const RemoteClient& client) {
         client.remove("/v1/models/" + *model_id);
         return kExitOk;
       });
  struct Embed {
    std::string id, payload, recipient, out, format;
    double strength = std::numeric_limits<double>::quiet_NaN();  // NaN: not given (the daemon's default)
  };
  auto embed = std::make_shared<Embed>();
  leaf(models, "embed", "Make a watermarked copy and download it", action,
       [embed](CLI::App* c) {
         c->add_option("id", embed->id, "Model id")->required();
         c->add_option("--payload", embed->payload, "Payload (hex)");
         c->add_option("--recipient", embed->recipient, "Who receives the copy (assigns a payload if none is given)");
         c->add_option("--strength", embed->strength, "Distortion budget (percent of the bbox diagonal)");
         c->add_option("--format", embed->format, "Format of the copy (default: the model's)");
         c->add_option("--out", embed->out, "Where to write the copy (default: <job id>.<format>)");
       },
       [embed](const RemoteClient& client) {
         nlohmann::json body = nlohmann::json::object();
         if (!embed->payload.empty()) body["payload"] = embed->payload;
         if (!embed->recipient.empty()) body["recipient"] = embed->recipient;
         if (!std::isnan(embed->strength)) body["strength"] = embed->strength;  // the daemon validates it
         // The copy's format: --format, else the --out file's extension, else the model's own.
         std::string format = embed->format;
         if (!embed->out.empty() && std::filesystem::path(embed->out).extension() != ".zip") {  // a ZIP: the model's own
           const std::string from_out = to_string(mesh_format_from_path(embed->out));  // throws for an unknown extension
           if (!format.empty() && format != from_out)
             throw std::invalid_argument("--format " + format + " contradicts --out " + embed->out + " (" + from_out + ")");
           format = from_out;
         }
         if (!format.empty()) body["format"] = format;
         const nlohmann::json accepted = client.post_json("/v1/models/" + embed->id + "/embed", body);
         const nlohmann::json job = client.wait_job(accepted["job_id"]);
         if (job["state"] != "succeeded") return finish_job(job);
         const std::string written_format = job["result"]["format"];
         const std::string out = embed->out.empty() ? job["id"].get<std::string>() + "." + written_format : embed->out;
         write_file_atomically(out, client.get_bytes("/v1/jobs/" + job["id"].get<std::string>() + "/result"));
         nlohmann::json summary = job["result"];
         summary["job_id"] = job["id"];
         summary["file"] = out;
         print(summary);
         return kExitOk;
       });
  struct Detect {
    std::string id, suspect;
  };
  auto detect = std::make_shared<Detect>();
  leaf(models, "detect", "Check a suspect mesh against a model", action,
       [detect](CLI::App* c) {
         c->add_option("id", detect->id, "Model id")->required();
         c->add_option("suspect", detect->suspect, "Suspect mesh file")->required();
       },
       [detect](const RemoteClient& client) {
         const std::string format = to_string(mesh_format_from_path(detect->suspect));
         const nlohmann::json accepted =
             client.post_file("/v1/models/" + detect->id + "/detect?format=" + format, read_file(detect->suspect));
         return finish_job(client.wait_job(accepted["job_id"]));
       });

  auto* jobs = app.add_subcommand("jobs", "Daemon: jobs");
  jobs->require_subcommand(1);
  auto job_id = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  leaf(jobs, "show", "Show a job", action, [job_id](CLI::App* c) { c->add_option("id", *job_id)->required(); },
       [job_id](const RemoteClient& client) {
         print(client.get_json("/v1/jobs/" + *job_id));
         return kExitOk;
       });
  leaf(jobs, "wait", "Wait until a job finishes", action, [job_id](CLI::App* c) { c->add_option("id", *job_id)->required(); },
       [job_id](const RemoteClient& client) { return finish_job(client.wait_job(*job_id)); });
  leaf(jobs, "result", "Download a job's result", action,
       [job_id, out](CLI::App* c) {
         c->add_option("id", *job_id)->required();
         c->add_option("--out", *out, "File to write (default: standard output)");
       },
       [job_id, out](const RemoteClient& client) {
         const std::string bytes = client.get_bytes("/v1/jobs/" + *job_id + "/result");
         if (out->empty()) std::cout << bytes;
         else write_file_atomically(*out, bytes);
         return kExitOk;
       });
  leaf(jobs, "cancel", "Cancel a job", action, [job_id](CLI::App* c) { c->add_option("id", *job_id)->required(); },
       [job_id](const RemoteClient& client) {
         client.remove("/v1/jobs/" + *job_id);
         return kExitOk;
       });

  leaf(&app, "health", "Exit 0 if the daemon answers /livez (for container health checks)", action, [](CLI::App*) {},
       [](const RemoteClient& client) {
         if (client.alive()) return kExitOk;
         std::cerr << "meshmark health: the daemon does not answer /livez\n";
         return kExitRefused;
       });
}

}  // namespace meshmark::cli
