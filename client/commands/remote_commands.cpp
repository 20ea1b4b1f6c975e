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
#include "proto/links.hpp"
#include "proto/states.hpp"

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
  return job.value("state", "") == to_string(JobState::succeeded) ? kExitOk : kExitRefused;
}

bool succeeded(const nlohmann::json& job) { return job.value("state", "") == to_string(JobState::succeeded); }

constexpr const char* kAdminToken = "MESHMARK_ADMIN_TOKEN";

// A command that takes one id and prints what GET returns for it.
void show_leaf(CLI::App* parent, const std::string& name, const std::string& help, Action& action,
               const std::function<std::string(const std::string&)>& path) {
  auto id = std::make_shared<std::string>();
  leaf(
      parent, name, help, action, [id](CLI::App* c) { c->add_option("id", *id)->required(); },
      [id, path](const RemoteClient& client) {
        print(client.get_json(path(*id)));
        return kExitOk;
      });
}

// A command that takes one id and DELETEs its resource.
void delete_leaf(CLI::App* parent, const std::string& name, const std::string& help, Action& action,
                 const std::function<std::string(const std::string&)>& path, const char* token_env = "MESHMARK_TOKEN") {
  auto id = std::make_shared<std::string>();
  leaf(
      parent, name, help, action, [id](CLI::App* c) { c->add_option("id", *id)->required(); },
      [id, path](const RemoteClient& client) {
        client.remove(path(*id));
        return kExitOk;
      },
      token_env);
}

void register_owners(CLI::App& app, Action& action) {
  auto* owners = app.add_subcommand("owners", "Daemon: owners (needs the admin token)");
  owners->require_subcommand(1);
  auto owner_name = std::make_shared<std::string>("owner");
  leaf(
      owners, "create", "Create an owner; prints its API key (shown once)", action,
      [owner_name](CLI::App* c) { c->add_option("--name", *owner_name, "Owner name"); },
      [owner_name](const RemoteClient& client) {
        print(client.post_json(links::owners(), {{"name", *owner_name}}));
        return kExitOk;
      },
      kAdminToken);
  leaf(
      owners, "list", "List the owners and whether their keys work", action, [](CLI::App*) {},
      [](const RemoteClient& client) {
        print(client.get_json(links::owners()));
        return kExitOk;
      },
      kAdminToken);
  auto owner_id = std::make_shared<std::string>();
  leaf(
      owners, "rotate-key", "Give an owner a new API key (printed once); the old one stops working", action,
      [owner_id](CLI::App* c) { c->add_option("id", *owner_id, "Owner id")->required(); },
      [owner_id](const RemoteClient& client) {
        print(client.post_json(links::owner_key(*owner_id), nlohmann::json::object()));
        return kExitOk;
      },
      kAdminToken);
  delete_leaf(owners, "revoke-key", "Revoke an owner's API key (until the next rotate-key)", action, links::owner_key,
              kAdminToken);
}

struct UploadArgs {
  std::string file, name;
  bool wait = false;
};

int upload_model(const RemoteClient& client, const UploadArgs& args) {
  const std::string format = to_string(mesh_format_from_path(args.file));
  const std::string name = args.name.empty() ? std::filesystem::path(args.file).stem().string() : args.name;
  nlohmann::json model = client.post_file(links::models() + "?format=" + format + "&name=" + encode_query_value(name),
                                          read_file(args.file));
  if (args.wait) {
    const nlohmann::json job = client.wait_job(model["job_id"]);
    model = client.get_json(links::model(model["id"].get<std::string>()));
    if (!succeeded(job)) model["job"] = job;
  }
  print(model);
  return model.value("state", "") == to_string(ModelState::failed) ? kExitRefused : kExitOk;
}

struct RemoteEmbedArgs {
  std::string id, payload, recipient, out, format;
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

int embed_copy(const RemoteClient& client, const RemoteEmbedArgs& args) {
  nlohmann::json body = nlohmann::json::object();
  if (!args.payload.empty()) body["payload"] = args.payload;
  if (!args.recipient.empty()) body["recipient"] = args.recipient;
  if (!std::isnan(args.strength)) body["strength"] = args.strength;  // the daemon validates it
  if (const std::string format = copy_format(args); !format.empty()) body["format"] = format;
  const nlohmann::json accepted = client.post_json(links::model_embed(args.id), body);
  const nlohmann::json job = client.wait_job(accepted["job_id"]);
  if (!succeeded(job)) return finish_job(job);
  const std::string job_id = job["id"];
  const std::string out = args.out.empty() ? job_id + "." + job["result"]["format"].get<std::string>() : args.out;
  write_file_atomically(out, client.get_bytes(links::job_result(job_id)));
  nlohmann::json summary = job["result"];
  summary["job_id"] = job_id;
  summary["file"] = out;
  print(summary);
  return kExitOk;
}

void register_models(CLI::App& app, Action& action) {
  auto* models = app.add_subcommand("models", "Daemon: your models (originals), copies and checks");
  models->require_subcommand(1);
  auto upload = std::make_shared<UploadArgs>();
  leaf(
      models, "upload", "Upload an original mesh", action,
      [upload](CLI::App* c) {
        c->add_option("file", upload->file, "Mesh file")->required();
        c->add_option("--name", upload->name, "Model name (default: the file name)");
        c->add_flag("--wait", upload->wait, "Wait until the model is prepared");
      },
      [upload](const RemoteClient& client) { return upload_model(client, *upload); });
  leaf(
      models, "list", "List your models", action, [](CLI::App*) {},
      [](const RemoteClient& client) {
        print(client.get_json(links::models()));
        return kExitOk;
      });
  show_leaf(models, "show", "Show a model", action, links::model);
  show_leaf(models, "embeddings", "The copies handed out", action, links::model_embeddings);
  delete_leaf(models, "delete", "Delete a model", action, links::model);
  auto embed = std::make_shared<RemoteEmbedArgs>();
  leaf(
      models, "embed", "Make a watermarked copy and download it", action,
      [embed](CLI::App* c) {
        c->add_option("id", embed->id, "Model id")->required();
        c->add_option("--payload", embed->payload, "Payload (hex)");
        c->add_option("--recipient", embed->recipient, "Who receives the copy (assigns a payload if none is given)");
        c->add_option("--strength", embed->strength, "Distortion budget (percent of the bbox diagonal)");
        c->add_option("--format", embed->format, "Format of the copy (default: the model's)");
        c->add_option("--out", embed->out, "Where to write the copy (default: <job id>.<format>)");
      },
      [embed](const RemoteClient& client) { return embed_copy(client, *embed); });
  auto detect = std::make_shared<std::pair<std::string, std::string>>();  // model id, suspect file
  leaf(
      models, "detect", "Check a suspect mesh against a model", action,
      [detect](CLI::App* c) {
        c->add_option("id", detect->first, "Model id")->required();
        c->add_option("suspect", detect->second, "Suspect mesh file")->required();
      },
      [detect](const RemoteClient& client) {
        const std::string format = to_string(mesh_format_from_path(detect->second));
        const nlohmann::json accepted =
            client.post_file(links::model_detect(detect->first) + "?format=" + format, read_file(detect->second));
        return finish_job(client.wait_job(accepted["job_id"]));
      });
}

void register_jobs(CLI::App& app, Action& action) {
  auto* jobs = app.add_subcommand("jobs", "Daemon: jobs");
  jobs->require_subcommand(1);
  show_leaf(jobs, "show", "Show a job", action, links::job);
  auto job_id = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  leaf(
      jobs, "wait", "Wait until a job finishes", action,
      [job_id](CLI::App* c) { c->add_option("id", *job_id)->required(); },
      [job_id](const RemoteClient& client) { return finish_job(client.wait_job(*job_id)); });
  leaf(
      jobs, "result", "Download a job's result", action,
      [job_id, out](CLI::App* c) {
        c->add_option("id", *job_id)->required();
        c->add_option("--out", *out, "File to write (default: standard output)");
      },
      [job_id, out](const RemoteClient& client) {
        const std::string bytes = client.get_bytes(links::job_result(*job_id));
        if (out->empty()) std::cout << bytes;
        else write_file_atomically(*out, bytes);
        return kExitOk;
      });
  delete_leaf(jobs, "cancel", "Cancel a job", action, links::job);
}

}  // namespace

void register_remote(CLI::App& app, Action& action) {
  register_owners(app, action);
  register_models(app, action);
  register_jobs(app, action);
  leaf(
      &app, "health", "Exit 0 if the daemon answers /livez (for container health checks)", action, [](CLI::App*) {},
      [](const RemoteClient& client) {
        if (client.alive()) return kExitOk;
        std::cerr << "meshmark health: the daemon does not answer /livez\n";
        return kExitRefused;
      });
}

}  // namespace meshmark::cli
