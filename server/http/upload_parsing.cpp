#include "server/http/upload_parsing.hpp"

#include <chrono>

#include "core/io/mesh_io_error.hpp"
#include "core/util/job_control.hpp"
#include "proto/json_text.hpp"
#include "server/http/api_error.hpp"
#include "server/model_cache.hpp"

namespace meshmark::server::handlers {

MeshFormat format_param(const HttpRequest& req) {
  const std::string name = req.query_value("format");
  if (name.empty()) throw InvalidRequest("say the mesh's format: ?format=" + known_mesh_formats());
  const auto format = parse_mesh_format(name);
  if (!format)
    throw InvalidRequest("unknown format '" + clip_for_message(name, 20) + "' (expected " + known_mesh_formats() + ")");
  return *format;
}

std::string name_param(const HttpRequest& req) {
  if (!req.has_query("name")) return "model";
  std::string name = req.query_value("name");
  if (name.empty() || name.size() > 200 || !is_printable_utf8(name))
    throw InvalidRequest("'name' must be 1 to 200 bytes of printable UTF-8, without bidirectional marks");
  return name;
}

DetectRequest detect_params(const HttpRequest& req) {
  try {
    return parse_detect_query(req.query_value("scheme"), req.query_value("wavelet"), req.query_value("bits"));
  } catch (const std::invalid_argument& e) {
    throw InvalidRequest(e.what());
  }
}

namespace {

// Reads an uploaded file (alone, or zipped with its companions) with the daemon's size limits,
// at most `max_vertices`, within the job time limit. Nothing when it holds more than that but
// the daemon's own limit is higher.
std::optional<PackagedDocument> read_upload(const std::string& bytes, MeshFormat format, std::size_t max_vertices,
                                            ApiContext& ctx) {
  JobControl budget;  // parsing runs here, not in a job: the same time limit, and SIGTERM stops it
  budget.deadline = std::chrono::steady_clock::now() + std::chrono::seconds(ctx.config.job_time_limit_seconds);
  budget.cancel = &ctx.draining;
  try {
    DocumentReadOptions options;
    options.limits = upload_read_options(ctx.config, &budget);
    options.limits.max_faces = faces_for_vertices(max_vertices);
    options.limits.max_vertices = max_vertices;
    return PackagedDocument(bytes, format, options, "the uploaded " + to_string(format) + " file");
  } catch (const MeshLimitError& e) {
    if (max_vertices < ctx.config.max_vertices) return std::nullopt;
    throw TooLarge(e.what());
  } catch (const MeshIoError& e) {
    std::string hint;
    if (!looks_zipped(bytes) && (format == MeshFormat::gltf || format == MeshFormat::obj))
      hint = " (a ." + to_string(format) + " with companion files travels as a ZIP of it and its files)";
    throw InvalidRequest(e.what() + hint);
  } catch (const TimeLimitExceeded&) {
    throw TooLarge("the file could not be read within the time limit of " +
                   std::to_string(ctx.config.job_time_limit_seconds) + " s");
  } catch (const Canceled&) {
    throw Unavailable("the daemon is shutting down; retry shortly");
  }
}

// Memory for reading a body as if it held `vertices`; 503 when the daemon's ceiling has no room.
MemoryReservation admit_upload(ApiContext& ctx, std::size_t body_bytes, std::size_t vertices) {
  const std::size_t cost = upload_memory_cost(body_bytes, vertices);
  if (cost > ctx.memory.ceiling())
    throw TooLarge("reading this file could take " + std::to_string(cost >> 20) +
                   " MiB; the daemon's memory ceiling is " + std::to_string(ctx.memory.ceiling() >> 20) + " MiB");
  ctx.models.make_room(cost);
  auto reservation = ctx.memory.try_reserve(cost);
  if (!reservation)
    throw Unavailable("the daemon's memory is taken by other uploads and jobs; retry shortly",
                      {{"retry_after_seconds", RetryAfter::unavailable}});
  return std::move(*reservation);
}

}  // namespace

ParsedUpload parse_upload(const HttpRequest& req, MeshFormat format, ApiContext& ctx) {
  if (req.body_bytes == 0) throw InvalidRequest("the body is empty; send the mesh file as the request body");
  const std::size_t body = req.body_bytes;
  const std::size_t assumed = std::min(ctx.config.max_vertices, body / kBodyBytesPerVertex + 1);
  MemoryReservation memory = admit_upload(ctx, body, assumed);
  std::string bytes = upload_bytes(req);
  auto document = read_upload(bytes, format, assumed, ctx);
  if (!document) {
    memory = MemoryReservation();
    memory = admit_upload(ctx, body, ctx.config.max_vertices);
    document = read_upload(bytes, format, ctx.config.max_vertices, ctx);
  }
  return {std::move(memory), std::move(bytes), std::move(*document)};
}

}  // namespace meshmark::server::handlers
