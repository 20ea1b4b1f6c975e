// A Draco stream's declared size, read before anything is decoded: right for what libdraco
// writes, and a stream that claims more than the limits is refused without decoding it.

#include "core/io/draco_primitive.hpp"

#include <gtest/gtest.h>

#include "core/io/mesh_io_error.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

std::string varint(std::uint64_t value) {
  std::string out;
  do {
    out += static_cast<char>((value & 0x7f) | (value > 0x7f ? 0x80 : 0));
    value >>= 7;
  } while (value);
  return out;
}

// The header of a triangle-mesh stream, bitstream 2.2, no metadata.
std::string header(char method) { return std::string("DRACO\x02\x02\x01", 8) + method + std::string("\0\0", 2); }

TEST(DracoPrimitive, TheDeclaredSizeOfWhatLibdracoWritesIsItsSize) {
  const Mesh& creature = test::procedural_mesh("creature");
  const std::string stream = draco_encode_positions(creature, 14);
  const auto declared = draco_declared(stream);
  ASSERT_TRUE(declared.has_value());
  EXPECT_EQ(declared->faces, static_cast<std::uint64_t>(creature.F.rows()));
  EXPECT_EQ(declared->vertices, static_cast<std::uint64_t>(creature.V.rows()));
  const Mesh decoded = draco_decode_positions(stream);
  EXPECT_EQ(decoded.F.rows(), creature.F.rows());
  const DracoLimits enough{static_cast<std::uint64_t>(creature.V.rows()),
                           static_cast<std::uint64_t>(creature.F.rows())};
  EXPECT_NO_THROW(DracoPrimitive(stream, 0, enough));
}

// A few bytes that claim 16M vertices and faces: refused by the limit, not by running out of
// memory in the decoder (which would size its tables by the claim).
TEST(DracoPrimitive, AStreamClaimingMoreThanTheLimitIsRefusedBeforeDecoding) {
  const std::uint64_t claim = 1u << 24;
  const std::string edgebreaker =
      header('\x01') + '\0' + varint(claim) + varint(claim) + '\0' + varint(claim) + varint(0) + std::string(64, '\0');
  const std::string sequential = header('\x00') + varint(claim) + varint(claim) + std::string(64, '\0');
  for (const std::string& stream : {edgebreaker, sequential}) {
    const auto declared = draco_declared(stream);
    ASSERT_TRUE(declared.has_value());
    EXPECT_EQ(declared->faces, claim);
    try {
      DracoPrimitive(stream, 0, {3'000'000, 6'000'000});
      FAIL() << "a stream claiming 16M faces was decoded";
    } catch (const MeshLimitError& e) {
      EXPECT_NE(std::string(e.what()).find("declares 16777216 vertices"), std::string::npos) << e.what();
    }
  }
}

// libdraco's stream with metadata spliced in after the 11-byte header (flag 0x8000), as the
// bitstream specification lays it out: per attribute its id and an element, then the mesh's.
std::string with_metadata(const std::string& stream, const std::string& metadata) {
  std::string out = stream.substr(0, 11) + metadata + stream.substr(11);
  out[10] = static_cast<char>(out[10] | 0x80);
  return out;
}
std::string metadata_entry(const std::string& name, const std::string& value) {
  return static_cast<char>(name.size()) + name + varint(value.size()) + value;
}

TEST(DracoPrimitive, MetadataIsSkippedToReadTheSizeAndTheMeshStillDecodes) {
  const Mesh& creature = test::procedural_mesh("creature");
  const std::string plain = draco_encode_positions(creature, 14);
  const std::string attribute = varint(1) + varint(0) + varint(1) + metadata_entry("name", "abc") + varint(0);
  const std::string mesh_own = varint(0) + varint(1) + "\x03sub" + varint(1) + metadata_entry("k", "v") + varint(0);
  const std::string stream = with_metadata(plain, attribute + mesh_own);
  const auto declared = draco_declared(stream);
  ASSERT_TRUE(declared.has_value());
  EXPECT_EQ(declared->faces, static_cast<std::uint64_t>(creature.F.rows()));
  const DracoPrimitive primitive(stream, 0, {1'000'000, 1'000'000});
  EXPECT_EQ(primitive.faces().rows(), creature.F.rows());
}

// Found by fuzzing: metadata ahead of a connectivity that claims gigabytes. Its size is read past
// the metadata; metadata that libdraco would size by a false claim is refused unread.
TEST(DracoPrimitive, AStreamWhoseSizeCannotBeReadIsNotDecoded) {
  const std::string plain = draco_encode_positions(test::procedural_mesh("creature"), 14);
  const std::string huge_value = varint(0) + varint(1) + metadata_entry("k", "") + varint(0);
  std::string bomb = with_metadata(plain, huge_value);
  bomb.replace(11 + 4, 1, varint(std::uint64_t{1} << 31));  // the value's size: 2 GiB, never there
  std::string nested = varint(0);
  for (int depth = 0; depth < 40; ++depth) nested += varint(0) + varint(1) + "\x01n";
  for (const std::string& stream : {bomb, with_metadata(plain, nested), std::string("DRACO\x02\x02\x00\x00\0\0", 11)}) {
    EXPECT_FALSE(draco_declared(stream).has_value());
    EXPECT_THROW(DracoPrimitive(stream, 0, {1'000'000, 1'000'000}), MeshIoError);
  }
}

TEST(DracoPrimitive, AHeaderThatCannotBeReadAheadDeclaresNothing) {
  EXPECT_FALSE(draco_declared("not draco").has_value());
  EXPECT_FALSE(draco_declared(header('\x01').substr(0, 9)).has_value());                     // cut short
  EXPECT_FALSE(draco_declared(std::string("DRACO\x02\x02\x00\x00\0\0", 11)).has_value());    // a point cloud
  EXPECT_FALSE(draco_declared(std::string("DRACO\x02\x02\x01\x01\0\x80", 11)).has_value());  // metadata cut short
}

}  // namespace
}  // namespace meshmark
