#include "core/io/write_mesh.hpp"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>

#include "core/io/number_text.hpp"
#include "core/util/atomic_file.hpp"

namespace meshmark {

namespace {

void append_number(std::string& out, long long value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

template <typename T>
void append_binary(std::string& out, T value, bool big_endian) {
  unsigned char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big))
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
  out.append(reinterpret_cast<const char*>(raw), sizeof(T));
}

void append_vertex_line(std::string& out, const char* prefix, const Mesh& mesh, Eigen::Index v,
                        const CoordinateText& text) {
  out += prefix;
  for (int k = 0; k < 3; ++k) {
    if (k) out += ' ';
    text.append(out, mesh.V(v, k));
  }
  out += '\n';
}

CoordinateText coordinate_text(const Mesh& mesh, const WriteOptions& options) {
  return options.lossless_text ? CoordinateText(0) : CoordinateText::of_points(mesh.V);
}

std::string write_obj(const Mesh& mesh, const WriteOptions& options) {
  std::string out = "# written by meshmark\n";
  const CoordinateText text = coordinate_text(mesh, options);
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) append_vertex_line(out, "v ", mesh, v, text);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    out += 'f';
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      append_number(out, static_cast<long long>(mesh.F(f, k)) + 1);
    }
    out += '\n';
  }
  return out;
}

std::string write_off(const Mesh& mesh, const WriteOptions& options) {
  std::string out = "OFF\n";
  append_number(out, static_cast<long long>(mesh.V.rows()));
  out += ' ';
  append_number(out, static_cast<long long>(mesh.F.rows()));
  out += " 0\n";
  const CoordinateText text = coordinate_text(mesh, options);
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) append_vertex_line(out, "", mesh, v, text);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    out += '3';
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      append_number(out, static_cast<long long>(mesh.F(f, k)));
    }
    out += '\n';
  }
  return out;
}

std::string write_ply(const Mesh& mesh, const WriteOptions& options) {
  const bool be = options.big_endian;
  std::string out = "ply\nformat ";
  out += !options.binary ? "ascii" : be ? "binary_big_endian" : "binary_little_endian";
  out += " 1.0\ncomment written by meshmark\nelement vertex " + std::to_string(mesh.V.rows()) +
         "\nproperty double x\nproperty double y\nproperty double z\nelement face " + std::to_string(mesh.F.rows()) +
         "\nproperty list uchar int vertex_indices\nend_header\n";
  if (!options.binary) {
    const CoordinateText text = coordinate_text(mesh, options);
    for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) append_vertex_line(out, "", mesh, v, text);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
      out += '3';
      for (int k = 0; k < 3; ++k) {
        out += ' ';
        append_number(out, static_cast<long long>(mesh.F(f, k)));
      }
      out += '\n';
    }
    return out;
  }
  out.reserve(out.size() + static_cast<std::size_t>(24 * mesh.V.rows() + 13 * mesh.F.rows()));
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    for (int k = 0; k < 3; ++k) append_binary(out, mesh.V(v, k), be);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    out += static_cast<char>(3);
    for (int k = 0; k < 3; ++k) append_binary(out, static_cast<std::int32_t>(mesh.F(f, k)), be);
  }
  return out;
}

Eigen::Vector3d face_normal(const Mesh& mesh, Eigen::Index f) {
  const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double length = n.norm();
  return length > 0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
}

std::string write_stl(const Mesh& mesh, const WriteOptions& options) {
  std::string out;
  if (!options.binary) {
    out = "solid meshmark\n";
    const CoordinateText text = coordinate_text(mesh, options);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
      const Eigen::Vector3d n = face_normal(mesh, f);
      out += "facet normal ";
      for (int k = 0; k < 3; ++k) {
        if (k) out += ' ';
        out += unit_vector_text()(n[k]);
      }
      out += "\nouter loop\n";
      for (int c = 0; c < 3; ++c) append_vertex_line(out, "vertex ", mesh, mesh.F(f, c), text);
      out += "endloop\nendfacet\n";
    }
    out += "endsolid meshmark\n";
    return out;
  }
  check_fits_float32(mesh);
  out.reserve(84 + 50 * static_cast<std::size_t>(mesh.F.rows()));
  out.assign(80, ' ');
  out.replace(0, 20, "binary STL, meshmark");
  append_binary(out, static_cast<std::uint32_t>(mesh.F.rows()), false);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d n = face_normal(mesh, f);
    for (int k = 0; k < 3; ++k) append_binary(out, static_cast<float>(n[k]), false);
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) append_binary(out, static_cast<float>(mesh.V(mesh.F(f, c), k)), false);
    append_binary(out, std::uint16_t{0}, false);
  }
  return out;
}

}  // namespace

// Binary STL holds 32-bit floats: refuse coordinates they cannot hold closely enough, rather than
// write a mesh that rounding moved by more than a watermark's size.
void check_fits_float32(const Mesh& mesh) {
  if (mesh.V.rows() == 0) return;
  const double diagonal = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
  double worst = 0;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    for (int k = 0; k < 3; ++k) {
      const double x = mesh.V(v, k);
      if (std::abs(x) > std::numeric_limits<float>::max())
        throw MeshIoError("coordinate " + std::to_string(x) +
                          " is beyond what binary STL's 32-bit floats hold; "
                          "write PLY, OBJ or OFF instead");
      worst = std::max(worst, std::abs(static_cast<double>(static_cast<float>(x)) - x));
    }
  if (worst > kMaxStlRounding * diagonal) {
    char text[200];
    std::snprintf(text, sizeof text, "%.2g%% of the bounding-box diagonal", 100 * worst / diagonal);
    throw MeshIoError(std::string("binary STL's 32-bit floats would move vertices by up to ") + text +
                      " (the mesh lies far from the origin for its size); write PLY, OBJ or OFF instead");
  }
}

std::string write_mesh_to_memory(const Mesh& mesh, MeshFormat format, const WriteOptions& options) {
  switch (format) {
    case MeshFormat::obj:
      return write_obj(mesh, options);
    case MeshFormat::off:
      return write_off(mesh, options);
    case MeshFormat::ply:
      return write_ply(mesh, options);
    case MeshFormat::stl:
      return write_stl(mesh, options);
    case MeshFormat::glb:
    case MeshFormat::gltf:
    case MeshFormat::threemf:
      break;
  }
  throw MeshIoError("a plain mesh is written as OBJ, OFF, PLY or STL; " + to_string(format) +
                    " files are written only over the document they were read from");
}

void write_mesh(const std::filesystem::path& path, const Mesh& mesh, const WriteOptions& options) {
  const std::string bytes = write_mesh_to_memory(mesh, mesh_format_from_path(path), options);
  try {
    write_file_atomically(path, bytes);
  } catch (const std::exception& e) {
    throw MeshIoError(e.what());
  }
}

}  // namespace meshmark
