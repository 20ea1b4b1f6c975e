#include "proto/copy_record.hpp"

#include <gtest/gtest.h>

namespace meshmark {
namespace {

CopyRecord sample() {
  return {"c0ffee15", "spread",   "linear-lifting",       "octa", 0.05, "ab12", 2930, 5856,
          "spot.obj", "copy.ply", "2026-12-02T00:00:00Z", "",     ""};
}

TEST(CopyRecord, RoundTripsThroughJson) {
  const CopyRecord back = copy_record_from_json(to_json(sample()));
  EXPECT_EQ(back.payload, "c0ffee15");
  EXPECT_EQ(back.base, "octa");
  EXPECT_EQ(back.original_digest, "ab12");
  EXPECT_EQ(back.original_vertices, 2930);
  EXPECT_EQ(to_json(sample())["payload_bits"], 32);
}

// A record names its copy's recipient when there is one; one written before, without, reads as none.
TEST(CopyRecord, KeepsTheRecipientWhenThereIsOne) {
  CopyRecord named = sample();
  named.recipient = "partner \"a\"";
  EXPECT_EQ(copy_record_from_json(to_json(named)).recipient, "partner \"a\"");
  EXPECT_FALSE(to_json(sample()).contains("recipient"));
  EXPECT_EQ(copy_record_from_json(to_json(sample())).recipient, "");
}

TEST(CopyRecord, RefusesWhatIsNotARecordOrIsNewer) {
  EXPECT_THROW(copy_record_from_json(nlohmann::json::object()), std::invalid_argument);
  nlohmann::json newer = to_json(sample());
  newer["meshmark_record"] = kCopyRecordVersion + 1;
  EXPECT_THROW(copy_record_from_json(newer), std::invalid_argument);
  nlohmann::json missing = to_json(sample());
  missing.erase("wavelet");
  EXPECT_THROW(copy_record_from_json(missing), std::invalid_argument);
}

}  // namespace
}  // namespace meshmark
