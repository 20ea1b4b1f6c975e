// Request targets as the daemon splits them: any bytes decode, or are refused, without a crash;
// decoded paths route or get "no route", and every answer serializes.

#include "proto/json_text.hpp"
#include "server/http/http_message.hpp"
#include "server/http/routes.hpp"
#include "tests/fuzz/fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string path;
  std::multimap<std::string, std::string> query;
  if (!meshmark::server::split_target(as_text(data, size), path, query)) return 0;
  for (const char* method : {"GET", "POST", "DELETE"}) (void)meshmark::server::match_route(method, path);
  nlohmann::json j = {{"path", path}};
  for (const auto& [k, v] : query) j[k] = v;
  (void)meshmark::json_text(j);
  (void)meshmark::clip_for_message(path);
  return 0;
}
