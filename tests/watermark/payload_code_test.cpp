#include "core/watermark/payload_code.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/util/keyed_random.hpp"

namespace meshmark {
namespace {

std::vector<double> soft_from(const Bits& coded, double amplitude) {
  std::vector<double> soft(coded.size());
  for (std::size_t i = 0; i < coded.size(); ++i) soft[i] = coded[i] ? amplitude : -amplitude;
  return soft;
}

TEST(PayloadCode, HexRoundTrips) {
  EXPECT_EQ(hex_from_bits(bits_from_hex("0123456789abcdef")), "0123456789abcdef");
  EXPECT_EQ(hex_from_bits(bits_from_hex("DEADbeef")), "deadbeef");
  EXPECT_EQ(bits_from_hex("a").size(), 4u);
}

TEST(PayloadCode, BadHexIsRefusedByPosition) {
  EXPECT_THROW(bits_from_hex(""), std::invalid_argument);
  try {
    bits_from_hex("12g4");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("character 3"), std::string::npos);
  }
}

TEST(PayloadCode, Crc16MatchesTheCcittFalseCheckValue) {
  // The standard check: CRC-16/CCITT-FALSE of ASCII "123456789" is 0x29B1.
  Bits bits;
  for (char c : std::string("123456789"))
    for (int b = 7; b >= 0; --b) bits.push_back((c >> b) & 1);
  EXPECT_EQ(hex_from_bits(crc16(bits)), "29b1");
}

TEST(PayloadCode, CodedLengthIsThreeTimesMessagePlusTail) {  // constraint length 9: 8 tail bits
  EXPECT_EQ(coded_length(64), 3 * (64 + 16 + 8));
  EXPECT_EQ(encode_payload(bits_from_hex("0123456789abcdef")).size(), 264u);
}

TEST(PayloadCode, CleanCodewordDecodesWithAMatchingChecksum) {
  const Bits payload = bits_from_hex("3f2a9c0d17e4b568");
  const DecodedPayload d = decode_payload(soft_from(encode_payload(payload), 1.0), 64);
  EXPECT_EQ(d.payload, payload);
  EXPECT_TRUE(d.checksum_ok);
  EXPECT_EQ(d.codeword, encode_payload(payload));
}

TEST(PayloadCode, CorrectsScatteredErrorsAndErasures) {
  const Bits payload = bits_from_hex("feedface01234567");
  std::vector<double> soft = soft_from(encode_payload(payload), 1.0);
  for (std::size_t i = 0; i < soft.size(); i += 17) soft[i] = -soft[i];  // 16 flipped coded bits
  for (std::size_t i = 5; i < soft.size(); i += 23) soft[i] = 0;         // and 11 erased
  const DecodedPayload d = decode_payload(soft, 64);
  EXPECT_EQ(d.payload, payload);
  EXPECT_TRUE(d.checksum_ok);
}

TEST(PayloadCode, DecodesThroughGaussianNoiseAtModerateSnr) {
  const Bits payload = bits_from_hex("0011223344556677");
  const Bits coded = encode_payload(payload);
  KeyedRandom r("test", "noise");
  int failures = 0;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> soft = soft_from(coded, 1.0);
    for (double& s : soft) {  // Box–Muller, σ = 1: coded-bit SNR 0 dB
      const double u1 = r.unit() + 1e-300, u2 = r.unit();
      s += std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
    }
    failures += decode_payload(soft, 64).payload != payload;
  }
  EXPECT_LE(failures, 1);
}

TEST(PayloadCode, NoiseOnlyRarelyPassesTheChecksum) {
  KeyedRandom r("test", "pure noise");
  int passed = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> soft(static_cast<std::size_t>(coded_length(64)));
    for (double& s : soft) s = r.unit() - 0.5;
    passed += decode_payload(soft, 64).checksum_ok;
  }
  EXPECT_LE(passed, 1);  // 2^-16 per trial
}

}  // namespace
}  // namespace meshmark
