#include "core/watermark/prepared_model_io.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "core/basis/multiscale_bumps.hpp"
#include "core/mesh/mesh_digest.hpp"
#include "core/mesh/mesh_report_io.hpp"
#include "core/util/binary_io.hpp"
#include "core/util/keyed_random.hpp"
#include "core/watermark/nuisance_fields.hpp"

namespace meshmark {

namespace {

constexpr char kMagic[] = "MESHMARK-PREPARED";
// 2: the parameterization's method and its statistics; 3: the basis (sphere, filled sphere, bumps)
// 4: the samples' normals, never read, are no longer stored. Version 3 files (copy records
// written before) still load: their normals are skipped. 5: detection's nuisance fields, which
// took longer to make (100 smoothing steps) than to load; version 4 files make them on first use.
// 6: the mesh's validation report, which took a third of loading a large model; versions 3 to 5
// validate the mesh again.
constexpr std::uint32_t kVersion = 6;
constexpr std::uint32_t kVersionWithoutReport = 5;
constexpr std::uint32_t kVersionWithoutNuisance = 4;
constexpr std::uint32_t kVersionWithSampleNormals = 3;

void put_distortion(BinaryWriter& w, const AreaDistortion& d) {
  for (double v : {d.min, d.p05, d.median, d.p95, d.max}) w.put(v);
}
AreaDistortion get_distortion(BinaryReader& r) {
  AreaDistortion d;
  for (double* v : {&d.min, &d.p05, &d.median, &d.p95, &d.max}) *v = r.get<double>();
  return d;
}

template <typename Location>
void put_locations(BinaryWriter& w, const std::vector<Location>& locations) {
  w.put(static_cast<std::uint64_t>(locations.size()));
  for (const auto& l : locations) {
    w.put(static_cast<std::int32_t>(l.face));
    for (int k = 0; k < 3; ++k) w.put(l.bary[k]);
  }
}
template <typename Location>
std::vector<Location> get_locations(BinaryReader& r, std::int64_t face_limit) {
  const auto n = r.get<std::uint64_t>();
  if (n > r.remaining() / 28) throw std::runtime_error("corrupt prepared model: too many locations");
  std::vector<Location> out(static_cast<std::size_t>(n));
  for (auto& l : out) {
    l.face = r.get<std::int32_t>();
    if (l.face < 0 || l.face >= face_limit)
      throw std::runtime_error("corrupt prepared model: a face index out of range");
    for (int k = 0; k < 3; ++k) l.bary[k] = r.get<double>();
  }
  return out;
}

void put_param(BinaryWriter& w, const SphereParam& p) {
  w.put_matrix(p.S);
  w.put(static_cast<std::uint8_t>(p.flipped_input));
  w.put(static_cast<std::uint64_t>(p.flipped_faces));
  w.put(p.degree);
  w.put(static_cast<std::uint8_t>(p.method));
  const ProgressiveSphereMap& pm = p.progressive;
  for (std::size_t v : {pm.collapses, pm.kernel_fallbacks, pm.relaxations}) w.put(static_cast<std::uint64_t>(v));
  w.put(static_cast<std::int32_t>(pm.levels));
  for (double v : {pm.coarsen_seconds, pm.refine_seconds, pm.final_seconds}) w.put(v);
  for (int v : {p.flow_iterations, p.factorizations, p.repair_rounds}) w.put(static_cast<std::int32_t>(v));
  w.put(static_cast<std::uint64_t>(p.flipped_before_repair));
  put_distortion(w, p.map_area_distortion);
  put_distortion(w, p.area_distortion);
  w.put(static_cast<std::uint64_t>(p.equalization.grid_levels.size()));
  for (int l : p.equalization.grid_levels) w.put(static_cast<std::int32_t>(l));
  for (int v : {p.equalization.steps, p.equalization.rejected_steps}) w.put(static_cast<std::int32_t>(v));
  for (double v : {p.equalization.spread_before, p.equalization.spread_after, p.equalization.time, p.map_seconds,
                   p.equalize_seconds, p.seconds})
    w.put(v);
}

SphereParam get_param(BinaryReader& r, const Faces& outward, Eigen::Index vertices) {
  SphereParam p;
  p.S = r.get_matrix<Vertices>();
  if (p.S.rows() != vertices || p.S.cols() != 3)
    throw std::runtime_error("corrupt prepared model: the map has the wrong size");
  p.F = outward;
  p.flipped_input = r.get<std::uint8_t>() != 0;
  p.flipped_faces = r.get<std::uint64_t>();
  p.degree = r.get<double>();
  const auto method = r.get<std::uint8_t>();
  if (method > 1) throw std::runtime_error("corrupt prepared model: unknown parameterization method");
  p.method = static_cast<SphereMethod>(method);
  ProgressiveSphereMap& pm = p.progressive;
  for (std::size_t* v : {&pm.collapses, &pm.kernel_fallbacks, &pm.relaxations}) *v = r.get<std::uint64_t>();
  pm.levels = r.get<std::int32_t>();
  for (double* v : {&pm.coarsen_seconds, &pm.refine_seconds, &pm.final_seconds}) *v = r.get<double>();
  for (int* v : {&p.flow_iterations, &p.factorizations, &p.repair_rounds}) *v = r.get<std::int32_t>();
  p.flipped_before_repair = r.get<std::uint64_t>();
  p.map_area_distortion = get_distortion(r);
  p.area_distortion = get_distortion(r);
  const auto levels = r.get<std::uint64_t>();
  if (levels > 16) throw std::runtime_error("corrupt prepared model");
  for (std::uint64_t i = 0; i < levels; ++i) p.equalization.grid_levels.push_back(r.get<std::int32_t>());
  for (int* v : {&p.equalization.steps, &p.equalization.rejected_steps}) *v = r.get<std::int32_t>();
  for (double* v : {&p.equalization.spread_before, &p.equalization.spread_after, &p.equalization.time, &p.map_seconds,
                    &p.equalize_seconds, &p.seconds})
    *v = r.get<double>();
  return p;
}

void put_bump_options(BinaryWriter& w, const BumpBasisOptions& o) {
  for (int v : {o.min_bumps, o.max_bands, o.min_component_vertices}) w.put(static_cast<std::int32_t>(v));
  for (double v : {o.finest_support_vertices, o.radius}) w.put(v);
}
BumpBasisOptions get_bump_options(BinaryReader& r) {
  BumpBasisOptions o;
  for (int* v : {&o.min_bumps, &o.max_bands, &o.min_component_vertices}) *v = r.get<std::int32_t>();
  for (double* v : {&o.finest_support_vertices, &o.radius}) *v = r.get<double>();
  if (o.min_bumps < 1 || o.max_bands < 1 || o.max_bands > 8 || !(o.radius > 0 && o.radius < 100) ||
      !(o.finest_support_vertices >= 1 && o.finest_support_vertices < 1e6) || o.min_component_vertices < 0)
    throw std::runtime_error("corrupt prepared model: bump options out of range");
  return o;
}

void put_sphere(BinaryWriter& w, const PreparedModel& m) {
  w.put(static_cast<std::uint8_t>(m.base));
  w.put(static_cast<std::int32_t>(m.grid->levels));
  if (m.basis == MeshBasis::sphere_filled) {
    w.put_matrix(m.filled.V);
    w.put_matrix(m.filled.F);
  }
  put_param(w, m.param);
  w.put(static_cast<std::int32_t>(m.sampling.level));
  w.put(m.sampling.error);
  w.put(static_cast<std::uint8_t>(m.sampling.reached_epsilon));
  w.put(static_cast<std::uint64_t>(m.sampling.error_by_level.size()));
  for (double e : m.sampling.error_by_level) w.put(e);
  put_locations(w, m.sampling.samples);
  w.put_matrix(m.sampling.positions);
  put_locations(w, m.sampling.vertex_cells);
}

void get_sphere(BinaryReader& r, PreparedModel& m, std::uint32_t version, GridCache* grids) {
  const Mesh& mesh = m.mesh;
  const auto base = r.get<std::uint8_t>();
  if (base > 2) throw std::runtime_error("corrupt prepared model: unknown base solid");
  m.base = static_cast<BaseSolid>(base);
  const auto levels = r.get<std::int32_t>();
  if (levels < 0 || levels > 12) throw std::runtime_error("corrupt prepared model: grid level out of range");
  m.grid = grids ? grids->get(m.base, levels) : std::make_shared<const SphereGrid>(make_sphere_grid(m.base, levels));
  if (m.basis == MeshBasis::sphere_filled) {
    m.filled.V = r.get_matrix<Vertices>();
    m.filled.F = r.get_matrix<Faces>();
    if (m.filled.V.rows() < mesh.V.rows() || m.filled.F.rows() < mesh.F.rows() || m.filled.V.cols() != 3 ||
        m.filled.F.cols() != 3 ||
        (m.filled.F.size() > 0 && (m.filled.F.minCoeff() < 0 || m.filled.F.maxCoeff() >= m.filled.V.rows())))
      throw std::runtime_error("corrupt prepared model: the filled surface does not fit the mesh");
  }
  const Mesh& surface = m.basis == MeshBasis::sphere_filled ? m.filled : mesh;
  const Faces& surface_outward = m.basis == MeshBasis::sphere_filled ? m.filled.F : m.outward;
  m.param = get_param(r, surface_outward, surface.V.rows());
  m.sampling.level = r.get<std::int32_t>();
  if (m.sampling.level < 0 || m.sampling.level > levels)
    throw std::runtime_error("corrupt prepared model: sampling level");
  m.sampling.error = r.get<double>();
  m.sampling.reached_epsilon = r.get<std::uint8_t>() != 0;
  const auto errors = r.get<std::uint64_t>();
  if (errors > 16) throw std::runtime_error("corrupt prepared model");
  for (std::uint64_t i = 0; i < errors; ++i) m.sampling.error_by_level.push_back(r.get<double>());
  m.sampling.samples = get_locations<SurfaceLocation>(r, surface.F.rows());
  m.sampling.positions = r.get_matrix<Eigen::MatrixXd>();
  m.sampling.vertex_cells =
      get_locations<GridLocation>(r, m.grid->faces[static_cast<std::size_t>(m.sampling.level)].rows());
  if (version == kVersionWithSampleNormals) r.get_matrix<Vertices>();
  const auto samples = static_cast<std::size_t>(m.grid->vertex_count(m.sampling.level));
  if (m.sampling.samples.size() != samples || static_cast<std::size_t>(m.sampling.positions.rows()) != samples ||
      m.sampling.vertex_cells.size() != static_cast<std::size_t>(mesh.V.rows()))
    throw std::runtime_error("corrupt prepared model: sample counts do not match the grid");
}

}  // namespace

std::string serialize_prepared_model(const PreparedModel& m) {
  BinaryWriter w;
  w.bytes().append(kMagic, sizeof(kMagic));
  w.put(kVersion);
  w.put(m.digest);
  put_mesh_report(w, m.report);
  w.put(static_cast<std::uint8_t>(m.basis));
  w.put(m.basis_reason);
  w.put_matrix(m.outward);
  w.put_matrix(m.normals);
  w.put_matrix(m.vertex_area);
  if (m.spherical()) put_sphere(w, m);
  else put_bump_options(w, m.bump_options);  // the bumps are rebuilt at load: cheap, and large to store
  w.put(m.prepare_seconds);
  w.put_matrix(nuisance_fields(m, 0));
  const auto digest = sha256(w.bytes());
  w.bytes().append(reinterpret_cast<const char*>(digest.data()), digest.size());
  return std::move(w.bytes());
}

PreparedModel deserialize_prepared_model(std::string_view bytes, const Mesh& mesh, GridCache* grids,
                                         const JobControl* control) {
  if (bytes.size() < sizeof(kMagic) + 32 || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
    throw std::runtime_error("not a prepared model file");
  const std::string_view content = bytes.substr(0, bytes.size() - 32);
  const auto digest = sha256(content);
  if (std::memcmp(digest.data(), bytes.data() + content.size(), 32) != 0)
    throw std::runtime_error("the prepared model file is corrupt (checksum mismatch)");
  BinaryReader r(content.substr(sizeof(kMagic)));
  const auto version = r.get<std::uint32_t>();
  if (version < kVersionWithSampleNormals || version > kVersion)
    throw std::runtime_error("the prepared model file has an unknown version");

  PreparedModel m;
  m.digest = r.get_string();
  if (m.digest != mesh_digest(mesh)) throw std::runtime_error("the prepared model was made from another mesh");
  m.mesh = mesh;
  m.report = version > kVersionWithoutReport ? get_mesh_report(r) : validate_mesh(mesh);
  if (m.report.vertices != static_cast<std::size_t>(mesh.V.rows()) ||
      m.report.faces != static_cast<std::size_t>(mesh.F.rows()) || !std::isfinite(m.report.bbox_diagonal) ||
      m.report.bbox_diagonal <= 0)
    throw std::runtime_error("corrupt prepared model: the report does not describe the mesh");
  m.diagonal = m.report.bbox_diagonal;
  const auto basis = r.get<std::uint8_t>();
  if (basis < static_cast<std::uint8_t>(MeshBasis::sphere) || basis > static_cast<std::uint8_t>(MeshBasis::bumps))
    throw std::runtime_error("corrupt prepared model: unknown basis");
  m.basis = static_cast<MeshBasis>(basis);
  m.basis_reason = r.get_string();
  m.outward = r.get_matrix<Faces>();
  if (m.outward.rows() != mesh.F.rows()) throw std::runtime_error("corrupt prepared model: face count differs");
  m.normals = r.get_matrix<Vertices>();
  m.vertex_area = r.get_matrix<Eigen::VectorXd>();
  if (m.normals.rows() != mesh.V.rows() || m.vertex_area.rows() != mesh.V.rows())
    throw std::runtime_error("corrupt prepared model: vertex count differs");
  if (m.spherical()) {
    get_sphere(r, m, version, grids);
  } else {
    m.bump_options = get_bump_options(r);
    m.bumps = std::make_shared<const BumpBasis>(multiscale_bumps(mesh, m.bump_options, control));
  }
  m.prepare_seconds = r.get<double>();
  if (version > kVersionWithoutNuisance) {
    Eigen::MatrixXd fields = r.get_matrix<Eigen::MatrixXd>();
    if (fields.rows() != mesh.V.rows() || fields.cols() != kNuisanceFieldCount)
      throw std::runtime_error("corrupt prepared model: the nuisance fields do not fit the mesh");
    std::call_once(m.nuisance->once, [&] { m.nuisance->value = std::move(fields); });
  }
  return m;
}

}  // namespace meshmark
