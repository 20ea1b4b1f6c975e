#include "core/mesh/mesh_report_io.hpp"

namespace meshmark {

namespace {

constexpr std::uint64_t kMaxListed = 1u << 16;  // examples and sentences: a handful each, ever

void put_strings(BinaryWriter& w, const std::vector<std::string>& strings) {
  w.put(static_cast<std::uint64_t>(strings.size()));
  for (const std::string& s : strings) w.put(s);
}

std::uint64_t get_count(BinaryReader& r) {
  const auto n = r.get<std::uint64_t>();
  if (n > kMaxListed || n > r.remaining()) throw std::runtime_error("corrupt mesh report: a list too long");
  return n;
}

std::vector<std::string> get_strings(BinaryReader& r) {
  std::vector<std::string> strings(get_count(r));
  for (std::string& s : strings) s = r.get_string();
  return strings;
}

template <std::size_t N>
void put_examples(BinaryWriter& w, const std::vector<std::array<int, N>>& examples) {
  w.put(static_cast<std::uint64_t>(examples.size()));
  for (const auto& e : examples)
    for (const int v : e) w.put(static_cast<std::int32_t>(v));
}

template <std::size_t N>
std::vector<std::array<int, N>> get_examples(BinaryReader& r) {
  std::vector<std::array<int, N>> examples(get_count(r));
  for (auto& e : examples)
    for (int& v : e) v = r.get<std::int32_t>();
  return examples;
}

// Single indices as one-element arrays, so that one pair of functions serves every list.
std::vector<std::array<int, 1>> as_arrays(const std::vector<int>& v) {
  std::vector<std::array<int, 1>> out;
  for (const int i : v) out.push_back({i});
  return out;
}
std::vector<int> as_ints(const std::vector<std::array<int, 1>>& v) {
  std::vector<int> out;
  for (const auto& a : v) out.push_back(a[0]);
  return out;
}

template <typename Enum>
Enum get_enum(BinaryReader& r, Enum last) {
  const auto value = r.get<std::uint8_t>();
  if (value > static_cast<std::uint8_t>(last)) throw std::runtime_error("corrupt mesh report: an unknown kind");
  return static_cast<Enum>(value);
}

}  // namespace

void put_mesh_report(BinaryWriter& w, const MeshReport& m) {
  for (const std::size_t n :
       {m.vertices, m.faces, m.components, m.boundary_edges, m.boundary_loops, m.nonmanifold_edges,
        m.nonmanifold_vertices, m.zero_area_faces, m.duplicate_vertices, m.isolated_vertices, m.marked_component_floor,
        m.small_components, m.small_component_vertices})
    w.put(static_cast<std::uint64_t>(n));
  w.put(static_cast<std::int64_t>(m.euler_characteristic));
  w.put(static_cast<std::uint8_t>(m.genus.has_value()));
  w.put(static_cast<std::int32_t>(m.genus.value_or(0)));
  w.put(static_cast<std::uint8_t>(m.orientation));
  w.put(m.bbox_diagonal);
  put_examples(w, as_arrays(m.nonmanifold_vertex_examples));
  put_examples(w, m.nonmanifold_edge_examples);
  put_examples(w, m.boundary_edge_examples);
  put_examples(w, as_arrays(m.zero_area_face_examples));
  w.put(static_cast<std::uint8_t>(m.closed_genus_zero));
  put_strings(w, m.sphere_problems);
  w.put(static_cast<std::uint8_t>(m.basis));
  w.put(m.basis_reason);
  w.put(static_cast<std::uint8_t>(m.valid));
  put_strings(w, m.problems);
  put_strings(w, m.warnings);
}

MeshReport get_mesh_report(BinaryReader& r) {
  MeshReport m;
  for (std::size_t* n :
       {&m.vertices, &m.faces, &m.components, &m.boundary_edges, &m.boundary_loops, &m.nonmanifold_edges,
        &m.nonmanifold_vertices, &m.zero_area_faces, &m.duplicate_vertices, &m.isolated_vertices,
        &m.marked_component_floor, &m.small_components, &m.small_component_vertices})
    *n = static_cast<std::size_t>(r.get<std::uint64_t>());
  m.euler_characteristic = r.get<std::int64_t>();
  const bool has_genus = r.get<std::uint8_t>() != 0;
  const auto genus = r.get<std::int32_t>();
  if (has_genus) m.genus = genus;
  m.orientation = get_enum(r, Orientation::inconsistent);
  m.bbox_diagonal = r.get<double>();
  m.nonmanifold_vertex_examples = as_ints(get_examples<1>(r));
  m.nonmanifold_edge_examples = get_examples<2>(r);
  m.boundary_edge_examples = get_examples<2>(r);
  m.zero_area_face_examples = as_ints(get_examples<1>(r));
  m.closed_genus_zero = r.get<std::uint8_t>() != 0;
  m.sphere_problems = get_strings(r);
  m.basis = get_enum(r, MeshBasis::bumps);
  m.basis_reason = r.get_string();
  m.valid = r.get<std::uint8_t>() != 0;
  m.problems = get_strings(r);
  m.warnings = get_strings(r);
  return m;
}

}  // namespace meshmark
