#include "core/io/gltf_components.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace meshmark::gltf {

std::size_t component_bytes(int type) {
  switch (type) {
    case kByte:
    case kUByte:
      return 1;
    case kShort:
    case kUShort:
      return 2;
    case kUInt:
    case kFloat:
      return 4;
    default:
      return 0;
  }
}

std::string type_name(int type) {
  switch (type) {
    case kByte:
      return "i8";
    case kUByte:
      return "u8";
    case kShort:
      return "i16";
    case kUShort:
      return "u16";
    case kUInt:
      return "u32";
    case kFloat:
      return "f32";
    default:
      return "?";
  }
}

int components_of(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4") return 4;
  return 0;
}

std::size_t element_bytes(const std::string& type, int component_type) {
  const std::size_t component = component_bytes(component_type);
  for (const std::size_t n : {2u, 3u, 4u})
    if (type == "MAT" + std::to_string(n)) return n * ((n * component + 3) / 4 * 4);
  return component * static_cast<std::size_t>(components_of(type));
}

double decode_component(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case kFloat: {
      float f;
      std::memcpy(&f, p, 4);
      return f;
    }
    case kByte: {
      const double v = static_cast<std::int8_t>(p[0]);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case kUByte:
      return normalized ? p[0] / 255.0 : p[0];
    case kShort: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case kUShort: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case kUInt: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    default:
      return 0;
  }
}

void encode_component(unsigned char* p, int type, bool normalized, double value) {
  const auto integer = [&](double scale, double lo, double hi) {
    const double r = std::nearbyint(normalized ? value * scale : value);
    return std::clamp(r, lo, hi);  // quantized positions at the edge of their range stay on it
  };
  switch (type) {
    case kFloat: {
      const float f = static_cast<float>(value);
      std::memcpy(p, &f, 4);
      break;
    }
    case kByte: {
      const auto v = static_cast<std::int8_t>(integer(127, -127, 127));
      std::memcpy(p, &v, 1);
      break;
    }
    case kUByte: {
      const auto v = static_cast<std::uint8_t>(integer(255, 0, 255));
      std::memcpy(p, &v, 1);
      break;
    }
    case kShort: {
      const auto v = static_cast<std::int16_t>(integer(32767, -32767, 32767));
      std::memcpy(p, &v, 2);
      break;
    }
    case kUShort: {
      const auto v = static_cast<std::uint16_t>(integer(65535, 0, 65535));
      std::memcpy(p, &v, 2);
      break;
    }
    case kUInt: {
      const auto v = static_cast<std::uint32_t>(integer(1, 0, 4294967295.0));
      std::memcpy(p, &v, 4);
      break;
    }
    default:
      break;
  }
}

StoredRange stored_range(int type, bool normalized) {
  const double inf = std::numeric_limits<double>::infinity();
  switch (type) {
    case kByte:
      return normalized ? StoredRange{-1, 1, 1 / 127.0} : StoredRange{-127, 127, 1};
    case kUByte:
      return normalized ? StoredRange{0, 1, 1 / 255.0} : StoredRange{0, 255, 1};
    case kShort:
      return normalized ? StoredRange{-1, 1, 1 / 32767.0} : StoredRange{-32767, 32767, 1};
    case kUShort:
      return normalized ? StoredRange{0, 1, 1 / 65535.0} : StoredRange{0, 65535, 1};
    case kUInt:
      return {0, 4294967295.0, 1};
    default:
      return {-inf, inf, 0};
  }
}

void encode_direction(unsigned char* p, int type, bool normalized, const Eigen::Vector3d& unit, double length) {
  const Eigen::Vector3d wanted = unit * length;
  const double step = normalized ? stored_range(type, true).step : 0.0;
  Eigen::Vector3d best = wanted;
  if (step > 0) {
    double best_cost = std::numeric_limits<double>::infinity();
    for (int corner = 0; corner < 8; ++corner) {
      Eigen::Vector3d q;
      for (int k = 0; k < 3; ++k)
        q[k] = ((corner >> k) & 1 ? std::ceil(wanted[k] / step) : std::floor(wanted[k] / step)) * step;
      const double cost = 100 * std::pow(q.norm() - length, 2) + (q - wanted).squaredNorm();
      if (cost < best_cost) {
        best_cost = cost;
        best = q;
      }
    }
  }
  for (int k = 0; k < 3; ++k) encode_component(p + k * component_bytes(type), type, normalized, best[k]);
}

}  // namespace meshmark::gltf
