#include "server/http/connection_counts.hpp"

#include <gtest/gtest.h>

namespace meshmark::server {
namespace {

using Admission = ConnectionCounts::Admission;

TEST(ConnectionCounts, OneClientFillsItsOwnCapNotTheServers) {
  ConnectionCounts counts(3, 2);
  EXPECT_EQ(counts.admit("a"), Admission::admitted);
  EXPECT_EQ(counts.admit("a"), Admission::admitted);
  EXPECT_EQ(counts.admit("a"), Admission::client_full);
  EXPECT_EQ(counts.admit("b"), Admission::admitted);
  EXPECT_EQ(counts.admit("c"), Admission::server_full);
  EXPECT_EQ(counts.total(), 3u);
  counts.release("a");
  EXPECT_EQ(counts.from("a"), 1u);
  EXPECT_EQ(counts.admit("c"), Admission::admitted);
  EXPECT_EQ(counts.total(), 3u);
}

TEST(ConnectionCounts, AReleasedClientIsForgottenAndAnUnknownReleaseChangesNothing) {
  ConnectionCounts counts(4, 4);
  ASSERT_EQ(counts.admit("a"), Admission::admitted);
  counts.release("a");
  counts.release("a");
  counts.release("never seen");
  EXPECT_EQ(counts.total(), 0u);
  EXPECT_EQ(counts.from("a"), 0u);
}

}  // namespace
}  // namespace meshmark::server
