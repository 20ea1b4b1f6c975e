#pragma once
// A ZIP archive of files, stored without compression: how tests package a .gltf with its
// companions the way a user's zip tool would (written here, not with the code under test).

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace meshmark::test {

inline std::uint32_t crc32_of(const std::string& data) {
  std::uint32_t crc = 0xffffffffu;
  for (const unsigned char byte : data) {
    crc ^= byte;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

/// The archive of (name, bytes) pairs, in order.
inline std::string stored_zip(const std::vector<std::pair<std::string, std::string>>& files) {
  const auto put = [](std::string& out, std::uint64_t value, int bytes) {
    for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>(value >> (8 * i) & 0xff));
  };
  std::string out, directory;
  for (const auto& [name, bytes] : files) {
    const std::uint32_t crc = crc32_of(bytes);
    const std::size_t offset = out.size();
    put(out, 0x04034b50, 4), put(out, 20, 2), put(out, 0, 2), put(out, 0, 2), put(out, 0, 4);
    put(out, crc, 4), put(out, bytes.size(), 4), put(out, bytes.size(), 4), put(out, name.size(), 2), put(out, 0, 2);
    out += name + bytes;
    put(directory, 0x02014b50, 4), put(directory, 20, 2), put(directory, 20, 2), put(directory, 0, 2), put(directory, 0, 2);
    put(directory, 0, 4), put(directory, crc, 4), put(directory, bytes.size(), 4), put(directory, bytes.size(), 4);
    put(directory, name.size(), 2), put(directory, 0, 2), put(directory, 0, 2), put(directory, 0, 2), put(directory, 0, 2);
    put(directory, 0, 4), put(directory, offset, 4);
    directory += name;
  }
  const std::size_t at = out.size();
  out += directory;
  put(out, 0x06054b50, 4), put(out, 0, 2), put(out, 0, 2), put(out, files.size(), 2), put(out, files.size(), 2);
  put(out, directory.size(), 4), put(out, at, 4), put(out, 0, 2);
  return out;
}

}  // namespace meshmark::test
