#include "tests/procedural_assets.hpp"

#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "tests/procedural_meshes.hpp"
#include "tests/test_data.hpp"

namespace meshmark::test {

namespace {

// The creature as a renderer stores it: float positions, normals and texture coordinates per
// stored vertex, vertices split where the texture's seam (u = 0 = 1) cuts faces.
struct TexturedMesh {
  std::vector<float> positions, normals, uvs;  // 3, 3, 2 per stored vertex
  std::vector<std::uint16_t> indices;
  std::size_t vertices() const { return positions.size() / 3; }
};

Eigen::Vector3d area_weighted_normal(const Mesh& mesh, Eigen::Index v, const std::vector<std::vector<int>>& faces_of) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (const int f : faces_of[static_cast<std::size_t>(v)]) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
    n += (b - a).cross(c - a);
  }
  return n.normalized();
}

TexturedMesh textured_creature() {
  const Mesh mesh = creature(4);
  std::vector<std::vector<int>> faces_of(static_cast<std::size_t>(mesh.V.rows()));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) faces_of[static_cast<std::size_t>(mesh.F(f, c))].push_back(static_cast<int>(f));
  TexturedMesh out;
  std::map<std::pair<int, bool>, std::uint16_t> stored;  // (vertex, on the seam's far side) → index
  const auto u_of = [&](int v) { return 0.5 + std::atan2(mesh.V(v, 1), mesh.V(v, 0)) / (2 * M_PI); };
  const auto store = [&](int v, bool wrapped) {
    const auto [it, added] = stored.emplace(std::make_pair(v, wrapped), static_cast<std::uint16_t>(out.vertices()));
    if (added) {
      const Eigen::Vector3d n = area_weighted_normal(mesh, v, faces_of);
      for (int k = 0; k < 3; ++k) out.positions.push_back(static_cast<float>(mesh.V(v, k)));
      for (int k = 0; k < 3; ++k) out.normals.push_back(static_cast<float>(n[k]));
      const double height = mesh.V(v, 2) / mesh.V.row(v).norm();
      out.uvs.push_back(static_cast<float>(u_of(v) + (wrapped ? 1 : 0)));
      out.uvs.push_back(static_cast<float>(0.5 - std::asin(std::clamp(height, -1.0, 1.0)) / M_PI));
    }
    return it->second;
  };
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    double lo = 1, hi = 0;
    for (int c = 0; c < 3; ++c) lo = std::min(lo, u_of(mesh.F(f, c))), hi = std::max(hi, u_of(mesh.F(f, c)));
    const bool crosses_seam = hi - lo > 0.5;
    for (int c = 0; c < 3; ++c) out.indices.push_back(store(mesh.F(f, c), crosses_seam && u_of(mesh.F(f, c)) < 0.5));
  }
  return out;
}

void put(std::string& out, std::uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>(value >> (8 * i) & 0xff));
}
void put_big(std::string& out, std::uint32_t value) {
  for (int i = 3; i >= 0; --i) out.push_back(static_cast<char>(value >> (8 * i) & 0xff));
}
template <typename T>
std::string bytes_of(const std::vector<T>& values) {
  return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

std::string raw_deflate(const std::string& data) {
  z_stream z{};
  if (deflateInit2(&z, Z_BEST_COMPRESSION, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::runtime_error("deflateInit2");
  std::string out(deflateBound(&z, static_cast<uLong>(data.size())), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = static_cast<uInt>(data.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  const int status = deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  if (status != Z_STREAM_END) throw std::runtime_error("deflate");
  return out;
}

std::uint32_t crc_of(const std::string& data) {
  return static_cast<std::uint32_t>(
      crc32(0, reinterpret_cast<const Bytef*>(data.data()), static_cast<uInt>(data.size())));
}

// A 2×2 RGB PNG: what a texture file is to the documents (carried along, never decoded).
std::string texture_png() {
  const auto chunk = [](std::string& png, const std::string& type, const std::string& data) {
    put_big(png, static_cast<std::uint32_t>(data.size()));
    png += type + data;
    put_big(png, crc_of(type + data));
  };
  std::string header;
  put_big(header, 2), put_big(header, 2);
  header += std::string("\x08\x02\x00\x00\x00", 5);  // 8 bits, RGB, deflate, no filter, no interlace
  const std::string rows = std::string("\0\xff\x00\x00\x00\xff\x00", 7) + std::string("\0\x00\x00\xff\xff\xff\xff", 7);
  uLongf length = compressBound(static_cast<uLong>(rows.size()));
  std::string pixels(length, '\0');
  compress(reinterpret_cast<Bytef*>(pixels.data()), &length, reinterpret_cast<const Bytef*>(rows.data()),
           static_cast<uLong>(rows.size()));
  pixels.resize(length);
  std::string png = "\x89PNG\r\n\x1a\n";
  chunk(png, "IHDR", header);
  chunk(png, "IDAT", pixels);
  chunk(png, "IEND", "");
  return png;
}

// The glTF JSON of the textured creature, its buffer laid out as indices, positions, normals,
// texture coordinates (and `image_bytes` of the texture when it is embedded, else an uri).
nlohmann::json gltf_json(const TexturedMesh& m, const std::string& buffer_uri, std::size_t image_bytes) {
  const std::size_t n = m.vertices(), index_bytes = (m.indices.size() * 2 + 3) / 4 * 4;
  const std::size_t at_positions = index_bytes, at_normals = at_positions + 12 * n, at_uvs = at_normals + 12 * n,
                    at_image = at_uvs + 8 * n;
  nlohmann::json min = nlohmann::json::array({1e9, 1e9, 1e9}), max = nlohmann::json::array({-1e9, -1e9, -1e9});
  for (std::size_t v = 0; v < n; ++v)
    for (int k = 0; k < 3; ++k) {
      min[k] = std::min(min[k].get<double>(), static_cast<double>(m.positions[3 * v + k]));
      max[k] = std::max(max[k].get<double>(), static_cast<double>(m.positions[3 * v + k]));
    }
  // Arrays spelled out: a braced list of one element is an array to GCC but a copy to clang.
  using nlohmann::json;
  const auto array = [](std::initializer_list<json> items) {
    json a = json::array();
    for (const json& item : items) a.push_back(item);
    return a;
  };
  json j = json::object();
  j["asset"] = {{"version", "2.0"}, {"generator", "meshmark tests"}};
  j["scene"] = 0;
  j["scenes"] = array({{{"nodes", array({0})}}});
  j["nodes"] = array({{{"mesh", 0}, {"name", "creature"}}});
  const json attributes = {{"POSITION", 1}, {"NORMAL", 2}, {"TEXCOORD_0", 3}};
  j["meshes"] = array(
      {{{"name", "creature"}, {"primitives", array({{{"attributes", attributes}, {"indices", 0}, {"material", 0}}})}}});
  j["materials"] = array({{{"name", "skin"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  j["textures"] = array({{{"source", 0}}});
  j["accessors"] =
      array({{{"bufferView", 0}, {"componentType", 5123}, {"count", m.indices.size()}, {"type", "SCALAR"}},
             {{"bufferView", 1}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"}, {"min", min}, {"max", max}},
             {{"bufferView", 2}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"}},
             {{"bufferView", 3}, {"componentType", 5126}, {"count", n}, {"type", "VEC2"}}});
  j["bufferViews"] = array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", m.indices.size() * 2}, {"target", 34963}},
                            {{"buffer", 0}, {"byteOffset", at_positions}, {"byteLength", 12 * n}, {"target", 34962}},
                            {{"buffer", 0}, {"byteOffset", at_normals}, {"byteLength", 12 * n}, {"target", 34962}},
                            {{"buffer", 0}, {"byteOffset", at_uvs}, {"byteLength", 8 * n}, {"target", 34962}}});
  json buffer = {{"byteLength", at_image + image_bytes}};
  if (!buffer_uri.empty()) buffer["uri"] = buffer_uri;
  j["buffers"] = array({buffer});
  if (image_bytes > 0) {
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at_image}, {"byteLength", image_bytes}});
    j["images"] = array({{{"bufferView", 4}, {"mimeType", "image/png"}}});
  } else {
    j["images"] = array({{{"uri", "texture.png"}}});
  }
  return j;
}

std::string gltf_buffer(const TexturedMesh& m, const std::string& image) {
  std::string bin = bytes_of(m.indices);
  bin.resize((bin.size() + 3) / 4 * 4, '\0');
  return bin + bytes_of(m.positions) + bytes_of(m.normals) + bytes_of(m.uvs) + image;
}

std::string glb(const TexturedMesh& m) {
  const std::string image = texture_png();
  std::string json = gltf_json(m, "", image.size()).dump(), bin = gltf_buffer(m, image);
  json.resize((json.size() + 3) / 4 * 4, ' ');
  bin.resize((bin.size() + 3) / 4 * 4, '\0');
  std::string out = "glTF";
  put(out, 2, 4), put(out, 12 + 8 + json.size() + 8 + bin.size(), 4);
  put(out, json.size(), 4), out += "JSON" + json;
  put(out, bin.size(), 4), out += std::string("BIN\0", 4) + bin;
  return out;
}

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", x);
  return text;
}

std::string obj(const TexturedMesh& m) {
  std::string out = "# a creature made by the meshmark tests\nmtllib creature.mtl\n";
  for (std::size_t v = 0; v < m.vertices(); ++v)
    out += "v " + number(m.positions[3 * v]) + " " + number(m.positions[3 * v + 1]) + " " +
           number(m.positions[3 * v + 2]) + "\n";
  for (std::size_t v = 0; v < m.vertices(); ++v)
    out += "vt " + number(m.uvs[2 * v]) + " " + number(m.uvs[2 * v + 1]) + "\n";
  for (std::size_t v = 0; v < m.vertices(); ++v)
    out += "vn " + number(m.normals[3 * v]) + " " + number(m.normals[3 * v + 1]) + " " + number(m.normals[3 * v + 2]) +
           "\n";
  out += "usemtl skin\n";
  for (std::size_t f = 0; f < m.indices.size(); f += 3) {
    out += "f";
    for (int c = 0; c < 3; ++c) {
      const std::string i = std::to_string(m.indices[f + static_cast<std::size_t>(c)] + 1);
      out += " " + i + "/" + i + "/" + i;
    }
    out += "\n";
  }
  return out;
}

std::string ply(const Mesh& mesh) {
  std::string out =
      "ply\nformat binary_little_endian 1.0\ncomment a creature made by the meshmark tests\nelement vertex " +
      std::to_string(mesh.V.rows()) +
      "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\n"
      "property uchar blue\nelement face " +
      std::to_string(mesh.F.rows()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    for (int k = 0; k < 3; ++k) {
      const float x = static_cast<float>(mesh.V(v, k));
      out.append(reinterpret_cast<const char*>(&x), 4);
    }
    for (int k = 0; k < 3; ++k) out.push_back(static_cast<char>((v * (k + 3)) % 256));
  }
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    out.push_back(3);
    for (int c = 0; c < 3; ++c) put(out, static_cast<std::uint32_t>(mesh.F(f, c)), 4);
  }
  return out;
}

std::string stl(const Mesh& mesh) {
  std::string out = "a creature made by the meshmark tests";
  out.resize(80, ' ');
  put(out, static_cast<std::uint64_t>(mesh.F.rows()), 4);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    for (const Eigen::Vector3d& p : {n, a, b, c})
      for (int k = 0; k < 3; ++k) {
        const float x = static_cast<float>(p[k]);
        out.append(reinterpret_cast<const char*>(&x), 4);
      }
    put(out, 0, 2);
  }
  return out;
}

std::string threemf_model(const Mesh& mesh) {
  std::string out = R"(<?xml version="1.0" encoding="UTF-8"?>
<model unit="millimeter" xml:lang="en-US" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">
 <metadata name="Title">creature</metadata>
 <resources>
  <object id="1" type="model" name="creature"><mesh><vertices>
)";
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    out += "   <vertex x=\"" + number(10 * mesh.V(v, 0)) + "\" y=\"" + number(10 * mesh.V(v, 1)) + "\" z=\"" +
           number(10 * mesh.V(v, 2)) + "\"/>\n";
  out += "  </vertices><triangles>\n";
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    out += "   <triangle v1=\"" + std::to_string(mesh.F(f, 0)) + "\" v2=\"" + std::to_string(mesh.F(f, 1)) +
           "\" v3=\"" + std::to_string(mesh.F(f, 2)) + "\"/>\n";
  out +=
      "  </triangles></mesh></object>\n </resources>\n <build><item objectid=\"1\" transform=\"1 0 0 0 1 0 0 0 1 40 40 "
      "20\"/></build>\n</model>\n";
  return out;
}

void write(const std::filesystem::path& path, const std::string& bytes) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
}

// Writes the asset `kind` into `folder`; returns its main file.
std::filesystem::path write_asset(const std::string& kind, const std::filesystem::path& folder) {
  const TexturedMesh textured = textured_creature();
  const Mesh welded = creature(4);
  if (kind == "gltf") {
    write(folder / "texture.png", texture_png());
    write(folder / "creature.bin", gltf_buffer(textured, ""));
    write(folder / "creature.gltf", gltf_json(textured, "creature.bin", 0).dump(2));
    return folder / "creature.gltf";
  }
  if (kind == "glb") return write(folder / "creature.glb", glb(textured)), folder / "creature.glb";
  if (kind == "obj") {
    write(folder / "texture.png", texture_png());
    write(folder / "creature.mtl", "newmtl skin\nKd 0.8 0.7 0.6\nmap_Kd texture.png\n");
    write(folder / "creature.obj", obj(textured));
    return folder / "creature.obj";
  }
  if (kind == "ply") return write(folder / "creature.ply", ply(welded)), folder / "creature.ply";
  if (kind == "stl") return write(folder / "creature.stl", stl(welded)), folder / "creature.stl";
  if (kind == "3mf")
    return write(folder / "creature.3mf", threemf_package(threemf_model(welded))), folder / "creature.3mf";
  if (kind == "skinned-glb") return write(folder / "skinned.glb", skinned_glb()), folder / "skinned.glb";
  throw std::invalid_argument("no procedural asset of kind '" + kind + "'");
}

}  // namespace

std::filesystem::path procedural_asset(const std::string& kind) {
  static std::mutex mutex;
  static std::map<std::string, std::filesystem::path> written;
  static const std::filesystem::path root = process_temp_folder("meshmark-assets");
  std::lock_guard lock(mutex);
  if (auto it = written.find(kind); it != written.end()) return it->second;
  return written.emplace(kind, write_asset(kind, root / kind)).first->second;
}

std::filesystem::path named_asset(const std::string& name) {
  return name.rfind("procedural/", 0) == 0 ? procedural_asset(name.substr(std::string("procedural/").size()))
                                           : shared_asset(name);
}

std::string zip_of(const std::vector<std::pair<std::string, std::string>>& files, bool deflate) {
  const int method = deflate ? 8 : 0;
  std::string out, directory;
  for (const auto& [name, bytes] : files) {
    const std::string packed = deflate ? raw_deflate(bytes) : bytes;
    const std::uint32_t crc = crc_of(bytes);
    const std::size_t offset = out.size();
    put(out, 0x04034b50, 4), put(out, 20, 2), put(out, 0, 2), put(out, method, 2), put(out, 0, 4);
    put(out, crc, 4), put(out, packed.size(), 4), put(out, bytes.size(), 4), put(out, name.size(), 2), put(out, 0, 2);
    out += name + packed;
    put(directory, 0x02014b50, 4), put(directory, 20, 2), put(directory, 20, 2), put(directory, 0, 2),
        put(directory, method, 2);
    put(directory, 0, 4), put(directory, crc, 4), put(directory, packed.size(), 4), put(directory, bytes.size(), 4);
    put(directory, name.size(), 2), put(directory, 0, 2), put(directory, 0, 2), put(directory, 0, 2),
        put(directory, 0, 2);
    put(directory, 0, 4), put(directory, offset, 4);
    directory += name;
  }
  const std::size_t at = out.size();
  out += directory;
  put(out, 0x06054b50, 4), put(out, 0, 2), put(out, 0, 2), put(out, files.size(), 2), put(out, files.size(), 2);
  put(out, directory.size(), 4), put(out, at, 4), put(out, 0, 2);
  return out;
}

std::string threemf_package(const std::string& model) {
  const std::string content_types = R"(<?xml version="1.0" encoding="UTF-8"?>
<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">
 <Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>
 <Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>
 <Default Extension="png" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodeltexture"/>
</Types>
)";
  const std::string rels = R"(<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">
 <Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>
</Relationships>
)";
  const std::string model_rels = R"(<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">
 <Relationship Target="/3D/Textures/texture.png" Id="rel1" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dtexture"/>
</Relationships>
)";
  return zip_of({{"[Content_Types].xml", content_types},
                 {"_rels/.rels", rels},
                 {"3D/3dmodel.model", model},
                 {"3D/_rels/3dmodel.model.rels", model_rels},
                 {"3D/Textures/texture.png", texture_png()}});
}

}  // namespace meshmark::test
