// The records that outlast a hand-out: every copy an owner handed out, across the library (JSON
// or CSV), each model's history of detections, and a model's copies in one ZIP.

#include <optional>
#include <set>
#include <sstream>

#include "core/io/zip_archive.hpp"
#include "proto/json_text.hpp"

#include "server/http/api_error.hpp"
#include "server/http/handler_support.hpp"
#include "server/http/handlers.hpp"
#include "server/http/problem.hpp"
#include "server/http/views.hpp"
#include "server/store/blob_keys.hpp"
#include "server/store/store.hpp"

namespace meshmark::server::handlers {

namespace {

// A CSV field (RFC 4180 quoting); a name a spreadsheet would run as a formula is kept as text.
std::string csv_field(const std::string& text, bool user_text) {
  std::string value = text;
  if (user_text && !value.empty() && std::string("=+-@\t\r").find(value.front()) != std::string::npos)
    value.insert(0, "'");
  if (value.find_first_of(",\"\r\n") == std::string::npos) return value;
  std::string quoted = "\"";
  for (const char c : value) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string copies_csv(const std::vector<HandedOutCopy>& copies) {
  std::ostringstream out;
  out << "model_id,model_name,recipient,payload,created_at,state,embedding_id,job_id,parameters,requested_by\r\n";
  for (const HandedOutCopy& h : copies) {
    const EmbeddingRecord& e = h.copy;
    out << csv_field(e.model_id, false) << ',' << csv_field(h.model_name, true) << ',' << csv_field(e.recipient, true)
        << ',' << csv_field(e.payload, false) << ',' << csv_field(e.created_at, false) << ','
        << csv_field(to_string(e.state), false) << ',' << csv_field(e.id, false) << ',' << csv_field(e.job_id, false)
        << ',' << csv_field(e.parameters.dump(), false) << ',' << csv_field(e.requested_by, true) << "\r\n";
  }
  return out.str();
}

struct CopyFile {
  std::string name, bytes;
};

// The file of a copy as it was handed out ("<model>-<recipient>.<format>[.zip]"); none when its
// job or its file is gone.
std::optional<CopyFile> copy_file(ApiContext& ctx, const ModelRecord& m, const EmbeddingRecord& e) {
  const auto job = ctx.store.job_by_id(e.job_id);
  const auto* spec = job ? std::get_if<EmbedJobSpec>(&job->spec) : nullptr;
  if (!spec) return std::nullopt;
  auto bytes = ctx.blobs.get(output_key(job->id, spec->output_format));
  if (!bytes) return std::nullopt;
  const bool zipped = job->result.value("zipped", false);
  return CopyFile{file_safe(m.name + "-" + (e.recipient.empty() ? e.payload : e.recipient) + "." + spec->output_format +
                            (zipped ? ".zip" : "")),
                  std::move(*bytes)};
}

}  // namespace

HttpResponse download_copies(ApiContext& ctx, HttpRequest& req) {
  const ModelRecord m = owned_model(ctx, owner_of(req), req.path_params.at("id"));
  std::set<std::string> wanted;
  for (auto [it, end] = req.query.equal_range("recipient"); it != end; ++it) wanted.insert(it->second);
  std::vector<std::pair<std::string, std::string>> files;
  std::set<std::string> names;
  std::size_t bytes = 0;
  for (const EmbeddingRecord& e : ctx.store.embeddings(m.id)) {
    if (e.state != EmbeddingState::ready || (!wanted.empty() && !wanted.count(e.recipient))) continue;
    auto file = copy_file(ctx, m, e);
    if (!file) continue;
    if (!names.insert(file->name).second) file->name = e.payload + "-" + file->name;  // one recipient, two copies
    bytes += file->bytes.size();
    files.emplace_back(std::move(file->name), std::move(file->bytes));
  }
  if (files.empty()) throw NotFound(wanted.empty() ? "no copy of this model was handed out yet" : "no copy for them");
  const auto memory = ctx.memory.try_reserve(2 * bytes);  // the files, and the archive of them
  if (!memory)
    throw Unavailable("the daemon's memory cannot hold these copies now; retry, or ask for fewer (?recipient=)",
                      {{"retry_after_seconds", RetryAfter::unavailable}});
  HttpResponse r;
  r.content_type = "application/zip";
  r.body = write_zip(files);
  r.set_header("Content-Disposition", "attachment; filename=\"" + file_safe(m.name) + "-copies.zip\"");
  return r;
}

HttpResponse export_embeddings(ApiContext& ctx, HttpRequest& req) {
  const std::string format = req.query_value("format");
  if (!format.empty() && format != "json" && format != "csv")
    throw InvalidRequest("format must be json or csv, not '" + format + "'");
  const std::vector<HandedOutCopy> copies = ctx.store.owner_embeddings(owner_of(req).id);
  if (format == "csv") {
    HttpResponse r;
    r.content_type = "text/csv; charset=utf-8";
    r.body = copies_csv(copies);
    return r;
  }
  nlohmann::json list = nlohmann::json::array();
  for (const HandedOutCopy& h : copies) list.push_back(handed_out_view(h));
  return json_response(200, {{"embeddings", list}});
}

HttpResponse list_detections(ApiContext& ctx, HttpRequest& req) {
  const OwnerRecord& owner = owner_of(req);
  const ModelRecord m = owned_model(ctx, owner, req.path_params.at("id"));
  nlohmann::json list = nlohmann::json::array();
  for (const JobRecord& j : ctx.store.model_jobs(owner.id, m.id, JobKind::detect)) list.push_back(detection_view(j));
  return json_response(200, {{"detections", list}});
}

}  // namespace meshmark::server::handlers
