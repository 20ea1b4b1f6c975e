#pragma once

#include <string>

namespace meshmark {

/// The OpenAPI document of the HTTP API (proto/openapi.json, compiled in).
const std::string& openapi_document();

}  // namespace meshmark
