#include "client/commands/remote_leaf.hpp"

#include <cstdio>
#include <iostream>

#include "client/terminal_progress.hpp"
#include "proto/states.hpp"

namespace meshmark::cli {

namespace {

struct Connection {
  std::string server = "http://127.0.0.1:8080";
  std::string token;
  Output output;
};

void print_answer(const Answer& answer, const Output& output) {
  if (output.json) {
    std::cout << answer.details.dump(2) << "\n";
    return;
  }
  if (!answer.line.empty()) std::cout << answer.line << "\n";
  if (!answer.evidence.empty()) std::cout << answer.evidence;
  else if (answer.details_in_words) std::cout << readable(answer.details);
}

std::string scalar_text(const nlohmann::json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_null()) return "-";
  return value.dump();
}

}  // namespace

void remote_leaf(CLI::App* parent, const std::string& name, const std::string& help, Action& action,
                 const std::function<void(CLI::App*)>& options, RemoteBody body, const char* token_env) {
  auto* cmd = parent->add_subcommand(name, help);
  auto c = std::make_shared<Connection>();
  cmd->add_option("--server", c->server, "Daemon URL")->envname("MESHMARK_SERVER")->capture_default_str();
  cmd->add_option("--token", c->token, std::string("API key (or $") + token_env + ")")->envname(token_env);
  cmd->add_flag("--json", c->output.json, "Print the daemon's JSON (for scripts) instead of sentences");
  cmd->add_flag("--quiet", c->output.quiet, "No progress on the terminal");
  options(cmd);
  cmd->callback([&action, c, body = std::move(body)] {
    action = [c, body] {
      try {
        const Answer answer = body(RemoteClient(c->server, c->token), c->output);
        print_answer(answer, c->output);
        return answer.status;
      } catch (const RemoteError& e) {
        std::fprintf(stderr, "meshmark: %s\n", e.what());
        return kExitError;
      }
    };
  });
}

std::string readable(const nlohmann::json& details, int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  std::string out;
  if (details.is_object()) {
    for (const auto& [key, value] : details.items()) {
      if (value.is_structured() && !value.empty()) out += pad + key + ":\n" + readable(value, indent + 2);
      else out += pad + key + ": " + (value.is_structured() ? std::string("(none)") : scalar_text(value)) + "\n";
    }
  } else if (details.is_array()) {
    for (const auto& item : details) {
      if (!item.is_structured()) {
        out += pad + "- " + scalar_text(item) + "\n";
        continue;
      }
      const std::string nested = readable(item, indent + 2);  // "- " takes the first line's indent
      out += pad + "- " + nested.substr(std::min(nested.size(), static_cast<std::size_t>(indent + 2)));
    }
  } else if (!details.is_null()) {
    out += pad + scalar_text(details) + "\n";
  }
  return out;
}

nlohmann::json wait_with_progress(const RemoteClient& client, const std::string& job_id, const std::string& what,
                                  const Output& output) {
  const TerminalProgress progress(what, !output.quiet && !output.json, 1);
  return client.wait_job(job_id, [&](const nlohmann::json& job) {
    if (progress.control()->report) progress.control()->report(job.value("stage", ""), job.value("progress", 0.0));
  });
}

bool succeeded(const nlohmann::json& job) { return job.value("state", "") == to_string(JobState::succeeded); }

Answer unsuccessful(const nlohmann::json& job) {
  std::string line = "job " + job.value("id", std::string("?")) + " " + job.value("state", std::string("ended"));
  if (const auto& error = job.value("error", nlohmann::json()); error.is_string() && !error.get<std::string>().empty())
    line += ": " + error.get<std::string>();
  return {line, job, kExitRefused};
}

}  // namespace meshmark::cli
