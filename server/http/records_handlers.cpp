// The records that outlast a hand-out: every copy an owner handed out, across the library (JSON
// or CSV), and each model's history of detections.

#include <sstream>

#include "server/http/api_error.hpp"
#include "server/http/handler_support.hpp"
#include "server/http/handlers.hpp"
#include "server/http/problem.hpp"
#include "server/http/views.hpp"
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
  out << "model_id,model_name,recipient,payload,created_at,state,embedding_id,job_id,parameters\r\n";
  for (const HandedOutCopy& h : copies) {
    const EmbeddingRecord& e = h.copy;
    out << csv_field(e.model_id, false) << ',' << csv_field(h.model_name, true) << ',' << csv_field(e.recipient, true)
        << ',' << csv_field(e.payload, false) << ',' << csv_field(e.created_at, false) << ','
        << csv_field(to_string(e.state), false) << ',' << csv_field(e.id, false) << ',' << csv_field(e.job_id, false)
        << ',' << csv_field(e.parameters.dump(), false) << "\r\n";
  }
  return out.str();
}

}  // namespace

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
