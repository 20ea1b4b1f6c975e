#pragma once
// The payload's protection: a CRC-16 to recognise a correct decode, and a convolutional code
// (constraint length 9, rate 1/3, generators 557, 663, 711 octal as in IS-95, zero-terminated)
// decoded by a soft-decision Viterbi decoder.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace meshmark {

using Bits = std::vector<std::uint8_t>;  ///< one bit (0 or 1) per element, most significant first

/// Hex digits (4 bits each, no prefix, case-insensitive) → bits. Throws std::invalid_argument
/// naming the bad character; an empty string is refused.
Bits bits_from_hex(const std::string& hex);
/// Bits (a multiple of 4) → lower-case hex.
std::string hex_from_bits(const Bits& bits);

/// CRC-16/CCITT-FALSE (polynomial 0x1021, initial value 0xFFFF) of the bits, as 16 bits.
Bits crc16(const Bits& bits);

inline constexpr int kCrcBits = 16;
inline constexpr int kConstraintLength = 9;
inline constexpr int kCodeRate = 3;

/// Coded length for `payload_bits` payload bits: 3 · (payload + 16 + 8).
int coded_length(int payload_bits);

/// payload ‖ CRC-16 ‖ eight zero tail bits, convolutionally encoded.
Bits encode_payload(const Bits& payload);

struct DecodedPayload {
  Bits payload;  ///< the most likely payload (whether or not its checksum matches)
  bool checksum_ok = false;
  Bits codeword;  ///< the re-encoded most likely message: what the decoder chose
};

/// Soft-decision Viterbi decoding: `soft[i]` > 0 favours coded bit i = 1, its size is
/// coded_length(payload_bits); 0 marks an erasure.
DecodedPayload decode_payload(const std::vector<double>& soft, int payload_bits);

}  // namespace meshmark
