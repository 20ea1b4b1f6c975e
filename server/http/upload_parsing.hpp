#pragma once
// What an upload says and holds: its format and name from the query, a detection's settings, and
// the file itself read (alone, or zipped with its companions) under the daemon's size limits,
// its time limit and its memory ceiling.

#include <string>

#include "core/io/packaged_document.hpp"
#include "proto/api.hpp"
#include "server/http/handler_support.hpp"
#include "server/memory_budget.hpp"

namespace meshmark::server::handlers {

/// ?format=: 400 when absent or unknown.
MeshFormat format_param(const HttpRequest& req);
/// ?name= (default "model"): 400 unless 1 to 200 bytes of printable UTF-8.
std::string name_param(const HttpRequest& req);
/// ?scheme=&wavelet=&bits=: 400 for a value out of range.
DetectRequest detect_params(const HttpRequest& req);

struct ParsedUpload {
  MemoryReservation memory;  // held while the upload and what is made of it are in memory
  std::string bytes;
  PackagedDocument document;
};

/// Reads an upload under the daemon's memory ceiling: first as if it held as many vertices as its
/// size suggests; a file that holds more (compressed, zipped, quantized) is read again once the
/// memory for the daemon's whole vertex limit is free. 400, 413 or 503 with the reason.
ParsedUpload parse_upload(const HttpRequest& req, MeshFormat format, ApiContext& ctx);

}  // namespace meshmark::server::handlers
