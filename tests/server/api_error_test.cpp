// Typed errors and their one mapping to HTTP.

#include "server/http/api_error.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "server/store/storage_error.hpp"

namespace meshmark::server {
namespace {

HttpResponse answer_to(const std::exception_ptr& e) {
  HttpRequest request;
  request.method = "POST";
  request.path = "/v1/models";
  return error_response(e, request);
}

TEST(ApiError, EachKindHasItsStatus) {
  EXPECT_EQ(InvalidRequest("x").status(), 400);
  EXPECT_EQ(Unauthorized("x").status(), 401);
  EXPECT_EQ(NotFound("x").status(), 404);
  EXPECT_EQ(Conflict("x").status(), 409);
  EXPECT_EQ(TooLarge("x").status(), 413);
  EXPECT_EQ(Unprocessable("x").status(), 422);
  EXPECT_EQ(Unavailable("x").status(), 503);
}

TEST(ApiError, TheClientSeesTheDetailOfAnApiError) {
  const HttpResponse r =
      answer_to(std::make_exception_ptr(Conflict("the model is still preparing", {{"state", "preparing"}})));
  EXPECT_EQ(r.status, 409);
  const auto body = nlohmann::json::parse(r.body);
  EXPECT_EQ(body["detail"], "the model is still preparing");
  EXPECT_EQ(body["state"], "preparing");
}

TEST(ApiError, AnUnavailableAnswerSaysWhenToRetry) {
  const HttpResponse r = answer_to(std::make_exception_ptr(Unavailable("the queue is full")));
  EXPECT_EQ(header_value(r.headers, "Retry-After"), std::to_string(RetryAfter::unavailable));
}

TEST(ApiError, AFullStoreIs507WithARetry) {
  const HttpResponse r =
      answer_to(std::make_exception_ptr(StorageError("disk full (SQLITE_FULL)", StorageError::Kind::full)));
  EXPECT_EQ(r.status, 507);
  EXPECT_EQ(header_value(r.headers, "Retry-After"), std::to_string(RetryAfter::storage_full));
  EXPECT_EQ(r.body.find("SQLITE"), std::string::npos) << r.body;
}

TEST(ApiError, AStoreThatDidNotAnswerIs503WithARetry) {
  const HttpResponse r =
      answer_to(std::make_exception_ptr(StorageError("server closed the connection", StorageError::Kind::unavailable)));
  EXPECT_EQ(r.status, 503);
  EXPECT_EQ(header_value(r.headers, "Retry-After"), std::to_string(RetryAfter::unavailable));
  EXPECT_EQ(r.body.find("connection"), std::string::npos) << r.body;
}

TEST(ApiError, APermanentStorageFailureIs500WithoutItsText) {
  const HttpResponse r =
      answer_to(std::make_exception_ptr(StorageError("SQLITE_CORRUPT at page 7", StorageError::Kind::permanent)));
  EXPECT_EQ(r.status, 500);
  EXPECT_TRUE(header_value(r.headers, "Retry-After").empty());
  EXPECT_EQ(r.body.find("SQLITE"), std::string::npos) << r.body;
}

TEST(ApiError, AnyOtherFailureIsAnInternalErrorWithoutItsText) {
  const HttpResponse r = answer_to(std::make_exception_ptr(std::runtime_error("SQLITE_CORRUPT at page 7")));
  EXPECT_EQ(r.status, 500);
  EXPECT_EQ(r.body.find("SQLITE"), std::string::npos) << r.body;
}

}  // namespace
}  // namespace meshmark::server
