#pragma once
// What every `meshmark owners|models|jobs` command shares: the daemon's address and key, an
// answer in words — one plain line first, then the details — or, with --json, the daemon's JSON
// for scripts; progress of a job on a terminal; the daemon's refusals as errors (exit 2).

#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "client/commands/commands.hpp"
#include "client/remote_client.hpp"

namespace meshmark::cli {

/// What a remote command answers.
struct Answer {
  Answer(std::string line = {}, nlohmann::json details = {}, int status = kExitOk, std::string evidence = {})
      : line(std::move(line)), details(std::move(details)), status(status), evidence(std::move(evidence)) {}
  std::string line;        ///< the plain sentence printed first (none when empty)
  nlohmann::json details;  ///< printed after it as indented "key: value" lines; all of it with --json
  int status;
  std::string evidence;          ///< printed instead of the details' lines when not empty
  bool details_in_words = true;  ///< false: the line says it all (the details are for --json)
};

/// An answer whose line says it all (its details are for --json).
inline Answer plain(std::string line, nlohmann::json details, int status = kExitOk) {
  Answer a(std::move(line), std::move(details), status);
  a.details_in_words = false;
  return a;
}

/// How the user asked to be answered.
struct Output {
  bool json = false;
  bool quiet = false;  ///< no progress on the terminal
};

using RemoteBody = std::function<Answer(const RemoteClient& client, const Output& output)>;

inline constexpr const char* kOwnerToken = "MESHMARK_TOKEN";
inline constexpr const char* kAdminToken = "MESHMARK_ADMIN_TOKEN";

/// Registers `parent name`: --server, --token (from `token_env`), --json, --quiet and the
/// command's own `options`; its action prints what `body` answers.
void remote_leaf(CLI::App* parent, const std::string& name, const std::string& help, Action& action,
                 const std::function<void(CLI::App*)>& options, RemoteBody body, const char* token_env = kOwnerToken);

/// `details` as indented "key: value" lines (objects nested, lists one item per "-").
std::string readable(const nlohmann::json& details, int indent = 2);

/// Waits for a job, its stage and progress shown on a terminal unless `output` says otherwise.
nlohmann::json wait_with_progress(const RemoteClient& client, const std::string& job_id, const std::string& what,
                                  const Output& output);

/// `meshmark models …` (remote_models_commands.cpp).
void register_remote_models(CLI::App& app, Action& action);

bool succeeded(const nlohmann::json& job);
/// A job that did not succeed, in words ("job J failed: …"), exit 1.
Answer unsuccessful(const nlohmann::json& job);

}  // namespace meshmark::cli
