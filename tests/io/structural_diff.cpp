#include "tests/io/structural_diff.hpp"

#include <cstring>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

#include "core/io/zip_archive.hpp"

namespace meshmark::test {

namespace {

using Json = nlohmann::json;

std::string file_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> words_of(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

// --- glTF ------------------------------------------------------------------------------------

struct Gltf {
  Json json;
  std::vector<std::string> buffers;
};

Gltf parse_gltf(const std::string& bytes, const std::filesystem::path& folder) {
  Gltf g;
  std::string bin;
  if (bytes.rfind("glTF", 0) == 0) {
    std::uint32_t json_length, bin_length = 0;
    std::memcpy(&json_length, bytes.data() + 12, 4);
    g.json = Json::parse(bytes.substr(20, json_length));
    if (20 + json_length + 8 <= bytes.size()) {
      std::memcpy(&bin_length, bytes.data() + 20 + json_length, 4);
      bin = bytes.substr(20 + json_length + 8, bin_length);
    }
  } else {
    g.json = Json::parse(bytes);
  }
  for (const Json& b : g.json.value("buffers", Json::array()))
    g.buffers.push_back(b.contains("uri") ? file_bytes(folder / b["uri"].get<std::string>()) : bin);
  return g;
}

std::string gltf_difference(const std::string& a_bytes, const std::string& b_bytes,
                            const std::filesystem::path& a_folder, const std::filesystem::path& b_folder) {
  Gltf a = parse_gltf(a_bytes, a_folder), b = parse_gltf(b_bytes, b_folder);
  // Views that may change: those of position, normal and tangent accessors, and Draco streams.
  std::set<std::size_t> moving;
  for (const Json& mesh : a.json.value("meshes", Json::array()))
    for (const Json& p : mesh["primitives"]) {
      for (const char* attribute : {"POSITION", "NORMAL", "TANGENT"})
        if (p["attributes"].contains(attribute)) {
          const Json& accessor = a.json["accessors"][p["attributes"][attribute].get<std::size_t>()];
          if (accessor.contains("bufferView")) moving.insert(accessor["bufferView"].get<std::size_t>());
        }
      if (p.contains("extensions") && p["extensions"].contains("KHR_draco_mesh_compression"))
        moving.insert(p["extensions"]["KHR_draco_mesh_compression"]["bufferView"].get<std::size_t>());
    }
  const auto view_bytes = [](const Gltf& g, std::size_t v) {
    const Json& view = g.json["bufferViews"][v];
    return g.buffers.at(view["buffer"].get<std::size_t>())
        .substr(view.value("byteOffset", std::size_t{0}), view["byteLength"].get<std::size_t>());
  };
  for (std::size_t v = 0; v < a.json.value("bufferViews", Json::array()).size(); ++v)
    if (!moving.count(v) && view_bytes(a, v) != view_bytes(b, v))
      return "buffer view " + std::to_string(v) + " differs";
  // The JSON without what moving positions may change.
  for (Gltf* g : {&a, &b}) {
    for (Json& accessor : g->json["accessors"]) accessor.erase("min"), accessor.erase("max");
    for (Json& view : g->json["bufferViews"]) view.erase("byteOffset"), view.erase("byteLength");
    for (Json& buffer : g->json["buffers"]) buffer.erase("byteLength"), buffer.erase("uri");
    for (Json& node : g->json["nodes"]) node.erase("translation"), node.erase("matrix");
  }
  if (a.json != b.json) return "the JSON differs beyond bounds, lengths and node translations";
  return "";
}

// --- OBJ -------------------------------------------------------------------------------------

std::string obj_difference(const std::string& a, const std::string& b) {
  const auto la = lines_of(a), lb = lines_of(b);
  if (la.size() != lb.size()) return "line counts differ";
  for (std::size_t i = 0; i < la.size(); ++i) {
    const auto wa = words_of(la[i]), wb = words_of(lb[i]);
    const bool vertex = !wa.empty() && wa[0] == "v", normal = !wa.empty() && wa[0] == "vn";
    if (vertex || normal) {
      if (wb.empty() || wb[0] != wa[0] || wa.size() != wb.size())
        return "line " + std::to_string(i + 1) + " changed shape";
      for (std::size_t k = 4; k < wa.size(); ++k)
        if (wa[k] != wb[k]) return "line " + std::to_string(i + 1) + ": a field after x y z changed";
    } else if (la[i] != lb[i]) {
      return "line " + std::to_string(i + 1) + " differs: '" + la[i].substr(0, 60) + "'";
    }
  }
  return "";
}

// --- OFF -------------------------------------------------------------------------------------

std::string off_difference(const std::string& a, const std::string& b) {
  const auto la = lines_of(a), lb = lines_of(b);
  if (la.size() != lb.size()) return "line counts differ";
  // Header keyword, then counts, then the vertex lines (comments and blank lines anywhere).
  std::size_t content = 0, vertices = 0;
  for (std::size_t i = 0; i < la.size(); ++i) {
    const auto wa = words_of(la[i]), wb = words_of(lb[i]);
    const bool blank = wa.empty() || wa[0][0] == '#';
    if (!blank) ++content;
    if (!blank && content == 2) vertices = std::stoul(wa[0]);
    const bool vertex_line = !blank && content >= 3 && content < 3 + vertices;
    if (!vertex_line && la[i] != lb[i]) return "line " + std::to_string(i + 1) + " differs";
    if (vertex_line) {
      if (wa.size() != wb.size()) return "line " + std::to_string(i + 1) + " changed shape";
      for (std::size_t k = 3; k < wa.size(); ++k)
        if (wa[k] != wb[k] && la[0].find("NOFF") == std::string::npos)
          return "line " + std::to_string(i + 1) + ": a field after x y z changed";
    }
  }
  return "";
}

// --- PLY -------------------------------------------------------------------------------------

struct PlyProperty {
  std::string name, type, count_type;  // count_type set for lists
};
struct PlyElement {
  std::string name;
  std::size_t count;
  std::vector<PlyProperty> properties;
};

std::size_t type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "double" || t == "float64") return 8;
  return 4;
}

std::string ply_difference(const std::string& a, const std::string& b) {
  const std::size_t end = a.find("end_header");
  if (end == std::string::npos) return "no PLY header";
  const std::size_t body = a.find('\n', end) + 1;
  if (a.substr(0, body) != b.substr(0, body)) return "the headers differ";
  std::vector<PlyElement> elements;
  bool ascii = false, big = false;
  for (const std::string& line : lines_of(a.substr(0, body))) {
    const auto w = words_of(line);
    if (w.empty()) continue;
    if (w[0] == "format") ascii = w[1] == "ascii", big = w[1] == "binary_big_endian";
    if (w[0] == "element") elements.push_back({w[1], std::stoul(w[2]), {}});
    if (w[0] == "property" && w[1] == "list") elements.back().properties.push_back({w[4], w[3], w[2]});
    else if (w[0] == "property") elements.back().properties.push_back({w[2], w[1], ""});
  }
  const std::set<std::string> moving = {"x", "y", "z", "nx", "ny", "nz"};
  if (ascii) {
    const auto la = lines_of(a.substr(body)), lb = lines_of(b.substr(body));
    if (la.size() != lb.size()) return "line counts differ";
    std::size_t line = 0;
    for (const PlyElement& e : elements)
      for (std::size_t i = 0; i < e.count; ++i, ++line) {
        const auto wa = words_of(la[line]), wb = words_of(lb[line]);
        if (wa.size() != wb.size()) return e.name + " " + std::to_string(i) + " changed shape";
        for (std::size_t k = 0; k < wa.size(); ++k)
          if (wa[k] != wb[k] &&
              !(k < e.properties.size() && e.properties[k].count_type.empty() && moving.count(e.properties[k].name)))
            return e.name + " " + std::to_string(i) + ": field " + std::to_string(k) + " changed";
      }
    return "";
  }
  if (a.size() != b.size()) return "the sizes differ";
  std::size_t at = body;
  for (const PlyElement& e : elements)
    for (std::size_t i = 0; i < e.count; ++i)
      for (const PlyProperty& p : e.properties) {
        std::size_t length = type_size(p.type);
        if (!p.count_type.empty()) {
          std::uint64_t n = 0;
          const std::size_t c = type_size(p.count_type);
          for (std::size_t k = 0; k < c; ++k)
            n |= static_cast<std::uint64_t>(static_cast<unsigned char>(a[at + (big ? c - 1 - k : k)])) << (8 * k);
          length = c + n * type_size(p.type);
        }
        const bool may_change = p.count_type.empty() && moving.count(p.name) && e.name == "vertex";
        if (!may_change && a.compare(at, length, b, at, length) != 0)
          return e.name + " " + std::to_string(i) + ": property " + p.name + " changed";
        at += length;
      }
  if (a.compare(at, std::string::npos, b, at, std::string::npos) != 0) return "bytes after the elements differ";
  return "";
}

// --- STL -------------------------------------------------------------------------------------

std::string stl_difference(const std::string& a, const std::string& b) {
  std::uint32_t count = 0;
  if (a.size() >= 84) std::memcpy(&count, a.data() + 80, 4);
  if (a.size() >= 84 && a.size() == 84 + 50ull * count) {  // binary
    if (b.size() != a.size()) return "the sizes differ";
    if (a.compare(0, 84, b, 0, 84) != 0) return "the header or count differs";
    for (std::uint32_t f = 0; f < count; ++f)
      if (a.compare(84 + 50ull * f + 48, 2, b, 84 + 50ull * f + 48, 2) != 0)
        return "facet " + std::to_string(f) + ": its attribute bytes changed";
    return "";
  }
  const auto la = lines_of(a), lb = lines_of(b);
  if (la.size() != lb.size()) return "line counts differ";
  for (std::size_t i = 0; i < la.size(); ++i) {
    const auto wa = words_of(la[i]), wb = words_of(lb[i]);
    const bool numbers = !wa.empty() && (wa[0] == "vertex" || wa[0] == "facet");
    if (!numbers && la[i] != lb[i]) return "line " + std::to_string(i + 1) + " differs";
  }
  return "";
}

// --- 3MF -------------------------------------------------------------------------------------

std::string threemf_difference(const std::string& a, const std::string& b) {
  const ZipArchive za(a, 1u << 30, "original"), zb(b, 1u << 30, "marked");
  if (za.entries().size() != zb.entries().size()) return "the packages hold different parts";
  const std::regex value(R"#(\b([xyz])="[^"]*")#");
  for (const ZipEntry& e : za.entries()) {
    const ZipEntry* m = zb.find(e.name);
    if (!m) return "'" + e.name + "' is missing";
    if (e.name.size() > 6 && e.name.substr(e.name.size() - 6) == ".model") {
      const std::string ta = std::regex_replace(za.extract(e), value, "$1=\"#\""),
                        tb = std::regex_replace(zb.extract(*m), value, "$1=\"#\"");
      if (ta != tb) return "'" + e.name + "' differs beyond vertex coordinates";
    } else if (a.compare(e.data, e.compressed_size, b, m->data, m->compressed_size) != 0) {
      return "'" + e.name + "' differs";
    }
  }
  return "";
}

}  // namespace

std::string difference_outside_positions(const std::string& original, const std::string& marked, MeshFormat format,
                                         const std::filesystem::path& original_folder,
                                         const std::filesystem::path& marked_folder) {
  switch (format) {
    case MeshFormat::glb:
    case MeshFormat::gltf:
      return gltf_difference(original, marked, original_folder, marked_folder);
    case MeshFormat::obj:
      return obj_difference(original, marked);
    case MeshFormat::off:
      return off_difference(original, marked);
    case MeshFormat::ply:
      return ply_difference(original, marked);
    case MeshFormat::stl:
      return stl_difference(original, marked);
    case MeshFormat::threemf:
      return threemf_difference(original, marked);
  }
  return "unknown format";
}

std::string difference_outside_positions(const std::filesystem::path& original_path,
                                         const std::filesystem::path& marked_path) {
  return difference_outside_positions(file_bytes(original_path), file_bytes(marked_path),
                                      mesh_format_from_path(original_path), original_path.parent_path(),
                                      marked_path.parent_path());
}

}  // namespace meshmark::test
