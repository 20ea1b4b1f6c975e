#pragma once
// The keyed pseudo-random generator behind every secret choice of the watermark. Specified to
// the bit so that any machine and compiler reproduces it: the seed is HMAC-SHA256(key, label),
// the generator xoshiro256** (Blackman and Vigna), and ranges come from our own mappings, never
// from std::uniform_*_distribution (whose output the standard leaves to each library).

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace meshmark {

/// HMAC-SHA256(key, message): 32 bytes.
std::array<std::uint8_t, 32> hmac_sha256(std::string_view key, std::string_view message);

/// SHA-256 of bytes.
std::array<std::uint8_t, 32> sha256(std::string_view bytes);

/// Lower-case hex of bytes.
std::string to_hex(const std::uint8_t* bytes, std::size_t size);

/// SHA-256 of bytes, as 64 lower-case hex digits.
std::string sha256_hex(std::string_view bytes);

class KeyedRandom {
 public:
  /// Seeds from HMAC-SHA256(key, label): different labels give independent streams.
  KeyedRandom(std::string_view key, std::string_view label);

  /// The next 64 bits of xoshiro256**.
  std::uint64_t next();
  /// Uniform in [0, n), n > 0, without bias (Lemire's multiply-and-reject).
  std::uint64_t below(std::uint64_t n);
  /// ±1 with equal probability (the top bit).
  int sign() { return (next() >> 63) ? 1 : -1; }
  /// Uniform in [0, 1) with 53 random bits.
  double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Fisher–Yates shuffle of `items` in place.
  template <typename T>
  void shuffle(std::vector<T>& items) {
    for (std::size_t i = items.size(); i > 1; --i) std::swap(items[i - 1], items[below(i)]);
  }

 private:
  std::array<std::uint64_t, 4> s_{};
};

}  // namespace meshmark
