#pragma once
// glTF's stored numbers: the component types with their sizes and normalization rules, and how a
// value, or a direction that must stay unit, is stored back in them.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>

namespace meshmark::gltf {

inline constexpr int kByte = 5120, kUByte = 5121, kShort = 5122, kUShort = 5123, kUInt = 5125, kFloat = 5126;
inline constexpr std::uint32_t kGlbMagic = 0x46546C67, kJsonChunk = 0x4E4F534A, kBinChunk = 0x004E4942;

std::size_t component_bytes(int type);  ///< 0 for an unknown type
std::string type_name(int type);        ///< "f32", "u16", ...: for the parts a document lists

/// Components of a vector or scalar type (0 for a matrix: never read as a vertex attribute here).
int components_of(const std::string& type);

/// Bytes of one element, 0 for an unknown type: a matrix (skins' inverse bind matrices) stores
/// each column from a 4-byte boundary (glTF 2.0, "Data Alignment").
std::size_t element_bytes(const std::string& type, int component_type);

/// One component as stored → its value (glTF's normalization rules), and back.
double decode_component(const unsigned char* p, int type, bool normalized);
void encode_component(unsigned char* p, int type, bool normalized, double value);

/// The range an integer component holds, in decoded units, and its step; floats: unbounded.
struct StoredRange {
  double lo, hi, step;
};
StoredRange stored_range(int type, bool normalized);

/// A direction of length `length` stored in three components: for normalized integers, the
/// rounding (each component down or up) whose length is closest to `length`, then closest to the
/// direction, so that unit normals and tangents stay unit within what the type can hold.
void encode_direction(unsigned char* p, int type, bool normalized, const Eigen::Vector3d& unit, double length);

inline std::size_t align4(std::size_t n) { return (n + 3) / 4 * 4; }

}  // namespace meshmark::gltf
