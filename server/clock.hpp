#pragma once

#include <string>

namespace meshmark::server {

/// Now, as an ISO 8601 UTC timestamp with milliseconds ("2026-11-21T09:30:00.123Z"): sortable.
std::string now_iso8601();

}  // namespace meshmark::server
