#include "core/watermark/payload_code.hpp"

#include <array>
#include <limits>
#include <stdexcept>

namespace meshmark {

Bits bits_from_hex(const std::string& hex) {
  if (hex.empty()) throw std::invalid_argument("the payload is empty; give it as hex digits, e.g. 0123456789abcdef");
  Bits bits;
  bits.reserve(4 * hex.size());
  for (std::size_t i = 0; i < hex.size(); ++i) {
    const char c = hex[i];
    int v;
    if (c >= '0' && c <= '9') v = c - '0';
    else if (c >= 'a' && c <= 'f') v = c - 'a' + 10;
    else if (c >= 'A' && c <= 'F') v = c - 'A' + 10;
    else
      throw std::invalid_argument(std::string("the payload must be hex digits; character ") + std::to_string(i + 1) +
                                  " is '" + c + "'");
    for (int b = 3; b >= 0; --b) bits.push_back(static_cast<std::uint8_t>((v >> b) & 1));
  }
  return bits;
}

std::string hex_from_bits(const Bits& bits) {
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (std::size_t i = 0; i + 3 < bits.size(); i += 4)
    out += digits[(bits[i] << 3) | (bits[i + 1] << 2) | (bits[i + 2] << 1) | bits[i + 3]];
  return out;
}

Bits crc16(const Bits& bits) {
  std::uint16_t crc = 0xFFFF;
  for (std::uint8_t bit : bits) {
    const bool top = ((crc >> 15) & 1) != (bit & 1);
    crc = static_cast<std::uint16_t>(crc << 1);
    if (top) crc ^= 0x1021;
  }
  Bits out(kCrcBits);
  for (int i = 0; i < kCrcBits; ++i) out[i] = static_cast<std::uint8_t>((crc >> (15 - i)) & 1);
  return out;
}

namespace {

constexpr std::array<unsigned, kCodeRate> kGenerators = {0557, 0663, 0711};
constexpr int kStates = 1 << (kConstraintLength - 1);

// The three output bits for input `bit` entering a shift register holding `state` (the last six
// inputs, newest in the lowest bit).
std::array<std::uint8_t, kCodeRate> outputs(unsigned state, unsigned bit) {
  const unsigned reg = (bit << (kConstraintLength - 1)) | state;  // newest input on top
  std::array<std::uint8_t, kCodeRate> out{};
  for (int g = 0; g < kCodeRate; ++g) out[g] = static_cast<std::uint8_t>(__builtin_parity(reg & kGenerators[g]));
  return out;
}

unsigned next_state(unsigned state, unsigned bit) { return (state >> 1) | (bit << (kConstraintLength - 2)); }

Bits convolve(const Bits& message) {
  Bits coded;
  coded.reserve(kCodeRate * message.size());
  unsigned state = 0;
  for (std::uint8_t bit : message) {
    for (std::uint8_t o : outputs(state, bit)) coded.push_back(o);
    state = next_state(state, bit);
  }
  return coded;
}

Bits message_of(const Bits& payload) {
  Bits message = payload;
  const Bits crc = crc16(payload);
  message.insert(message.end(), crc.begin(), crc.end());
  message.insert(message.end(), kConstraintLength - 1, 0);
  return message;
}

}  // namespace

int coded_length(int payload_bits) { return kCodeRate * (payload_bits + kCrcBits + kConstraintLength - 1); }

Bits encode_payload(const Bits& payload) { return convolve(message_of(payload)); }

DecodedPayload decode_payload(const std::vector<double>& soft, int payload_bits) {
  const int steps = payload_bits + kCrcBits + kConstraintLength - 1;
  if (static_cast<int>(soft.size()) != kCodeRate * steps)
    throw std::invalid_argument("decode_payload: " + std::to_string(soft.size()) + " soft bits for a " +
                                std::to_string(kCodeRate * steps) + "-bit code");
  constexpr double kMinus = -std::numeric_limits<double>::infinity();
  std::vector<double> metric(kStates, kMinus), next(kStates);
  metric[0] = 0;
  std::vector<std::array<std::uint8_t, kStates>> came_from_bit(static_cast<std::size_t>(steps));
  std::vector<std::array<std::uint8_t, kStates>> came_from_low(static_cast<std::size_t>(steps));
  for (int t = 0; t < steps; ++t) {
    std::fill(next.begin(), next.end(), kMinus);
    const bool tail = t >= payload_bits + kCrcBits;  // only zeros enter during the tail
    for (unsigned s = 0; s < kStates; ++s) {
      if (metric[s] == kMinus) continue;
      for (unsigned bit = 0; bit <= (tail ? 0u : 1u); ++bit) {
        const auto out = outputs(s, bit);
        double m = metric[s];
        for (int g = 0; g < kCodeRate; ++g) m += out[g] ? soft[kCodeRate * t + g] : -soft[kCodeRate * t + g];
        const unsigned ns = next_state(s, bit);
        if (m > next[ns]) {  // ties keep the first (lowest) predecessor: deterministic
          next[ns] = m;
          came_from_bit[t][ns] = static_cast<std::uint8_t>(bit);
          came_from_low[t][ns] = static_cast<std::uint8_t>(s & 1);  // the bit shifted out
        }
      }
    }
    metric.swap(next);
  }
  Bits message(static_cast<std::size_t>(steps));
  unsigned state = 0;  // zero-terminated
  for (int t = steps - 1; t >= 0; --t) {
    message[t] = came_from_bit[t][state];
    state = ((state << 1) & (kStates - 1)) | came_from_low[t][state];
  }
  DecodedPayload result;
  result.payload.assign(message.begin(), message.begin() + payload_bits);
  const Bits crc(message.begin() + payload_bits, message.begin() + payload_bits + kCrcBits);
  result.checksum_ok = crc == crc16(result.payload);
  result.codeword = convolve(message);
  return result;
}

}  // namespace meshmark
