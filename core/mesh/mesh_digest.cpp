#include "core/mesh/mesh_digest.hpp"

#include <cstdint>
#include <bit>
#include <cstring>

#include "core/util/keyed_random.hpp"

namespace meshmark {

namespace {

template <typename T>
void append_le(std::string& out, T value) {
  unsigned char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big)
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
  out.append(reinterpret_cast<const char*>(raw), sizeof(T));
}

}  // namespace

std::string mesh_digest(const Mesh& mesh) {
  std::string bytes;
  bytes.reserve(static_cast<std::size_t>(16 + 24 * mesh.V.rows() + 12 * mesh.F.rows()));
  append_le(bytes, static_cast<std::uint64_t>(mesh.V.rows()));
  append_le(bytes, static_cast<std::uint64_t>(mesh.F.rows()));
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    for (int k = 0; k < 3; ++k) append_le(bytes, mesh.V(v, k));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) append_le(bytes, static_cast<std::int32_t>(mesh.F(f, k)));
  return sha256_hex(bytes);
}

}  // namespace meshmark
