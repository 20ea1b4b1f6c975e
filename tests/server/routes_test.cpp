#include "server/http/routes.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <set>

#include "proto/openapi.hpp"

namespace meshmark::server {
namespace {

std::set<std::pair<std::string, std::string>> openapi_routes() {
  const auto doc = nlohmann::json::parse(openapi_document());
  std::set<std::pair<std::string, std::string>> routes;
  for (const auto& [path, item] : doc.at("paths").items())
    for (const auto& [method, operation] : item.items()) {
      std::string upper = method;
      for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      routes.emplace(upper, path);
    }
  return routes;
}

TEST(Routes, TheRouteTableIsExactlyTheOpenApiDocument) {
  std::set<std::pair<std::string, std::string>> table;
  for (const Route& r : api_routes()) table.emplace(r.method, r.path);
  EXPECT_EQ(table, openapi_routes());
}

TEST(Routes, EveryOperationDocumentsItsResponsesAndErrorsAsProblems) {
  const auto doc = nlohmann::json::parse(openapi_document());
  for (const auto& [path, item] : doc.at("paths").items())
    for (const auto& [method, operation] : item.items()) {
      ASSERT_TRUE(operation.contains("responses")) << method << " " << path;
      for (const auto& [status, response] : operation["responses"].items()) {
        if (status[0] != '4' && status[0] != '5') continue;
        const bool shared = response.value("$ref", "") == "#/components/responses/Problem";
        const bool inline_problem =
            response.contains("content") && response["content"].contains("application/problem+json");
        EXPECT_TRUE(shared || inline_problem) << method << " " << path << " " << status;
      }
    }
}

TEST(Routes, ConcretePathsMapToTheirTemplates) {
  EXPECT_EQ(route_of("GET", "/v1/models/mdl_123"), "/v1/models/{id}");
  EXPECT_EQ(route_of("POST", "/v1/models/mdl_123/embed"), "/v1/models/{id}/embed");
  EXPECT_EQ(route_of("DELETE", "/v1/jobs/job_9"), "/v1/jobs/{id}");
  EXPECT_EQ(route_of("GET", "/v1/jobs/job_9/result"), "/v1/jobs/{id}/result");
  EXPECT_EQ(route_of("PUT", "/v1/models/mdl_123"), "other");
  EXPECT_EQ(route_of("GET", "/wp-admin"), "other");
}

}  // namespace
}  // namespace meshmark::server
