#include "proto/core_json.hpp"

namespace meshmark {

void to_json(nlohmann::json& j, const MeshReport& r) {
  j = nlohmann::json{
      {"vertices", r.vertices},
      {"faces", r.faces},
      {"components", r.components},
      {"boundary_edges", r.boundary_edges},
      {"boundary_loops", r.boundary_loops},
      {"nonmanifold_edges", r.nonmanifold_edges},
      {"nonmanifold_vertices", r.nonmanifold_vertices},
      {"zero_area_faces", r.zero_area_faces},
      {"duplicate_vertices", r.duplicate_vertices},
      {"isolated_vertices", r.isolated_vertices},
      {"euler_characteristic", r.euler_characteristic},
      {"genus", r.genus ? nlohmann::json(*r.genus) : nlohmann::json(nullptr)},
      {"orientation", to_string(r.orientation)},
      {"bbox_diagonal", r.bbox_diagonal},
      {"nonmanifold_vertex_examples", r.nonmanifold_vertex_examples},
      {"nonmanifold_edge_examples", r.nonmanifold_edge_examples},
      {"boundary_edge_examples", r.boundary_edge_examples},
      {"zero_area_face_examples", r.zero_area_face_examples},
      {"closed_genus_zero", r.closed_genus_zero},
      {"sphere_problems", r.sphere_problems},
      {"basis", to_string(r.basis)},
      {"basis_reason", r.basis_reason},
      {"small_components", r.small_components},
      {"valid", r.valid},
      {"problems", r.problems},
      {"warnings", r.warnings},
  };
}

}  // namespace meshmark

namespace meshmark {

void to_json(nlohmann::json& j, const AreaDistortion& d) {
  j = nlohmann::json{{"min", d.min}, {"p05", d.p05}, {"median", d.median},
                     {"p95", d.p95}, {"max", d.max}, {"spread_p95_p05", d.p05 > 0 ? d.p95 / d.p05 : 0.0}};
}

void to_json(nlohmann::json& j, const SphereParam& p) {
  j = nlohmann::json{{"method", to_string(p.method)},
                     {"flipped_faces", p.flipped_faces},
                     {"degree", p.degree},
                     {"flipped_input", p.flipped_input},
                     {"area_distortion", p.area_distortion},
                     {"map_area_distortion", p.map_area_distortion},
                     // Before the area-correcting step; the key predates the progressive map.
                     {"conformal_area_distortion", p.map_area_distortion},
                     {"area_equalization",
                      {{"grid_levels", p.equalization.grid_levels},
                       {"steps", p.equalization.steps},
                       {"rejected_steps", p.equalization.rejected_steps},
                       {"density_spread_before", p.equalization.spread_before},
                       {"density_spread_after", p.equalization.spread_after},
                       {"seconds", p.equalize_seconds}}},
                     {"map_seconds", p.map_seconds},
                     {"seconds", p.seconds}};
  if (p.method == SphereMethod::progressive) {
    const ProgressiveSphereMap& m = p.progressive;
    j["progressive"] = {{"collapses", m.collapses},
                        {"levels", m.levels},
                        {"kernel_fallbacks", m.kernel_fallbacks},
                        {"relaxations", m.relaxations},
                        {"coarsen_seconds", m.coarsen_seconds},
                        {"refine_seconds", m.refine_seconds},
                        {"final_seconds", m.final_seconds}};
  } else {
    j["iterations"] = p.flow_iterations;
    j["factorizations"] = p.factorizations;
    j["flipped_before_repair"] = p.flipped_before_repair;
    j["repair_rounds"] = p.repair_rounds;
    j["flow_seconds"] = p.map_seconds;
  }
}

}  // namespace meshmark

namespace meshmark {

void to_json(nlohmann::json& j, const SurfaceDistance& d) {
  j = nlohmann::json{{"mrms", d.mrms_relative()}, {"hausdorff", d.hausdorff_relative()},
                     {"mrms_absolute", d.mrms},   {"hausdorff_absolute", d.hausdorff},
                     {"rms_a_to_b", d.rms_ab},    {"rms_b_to_a", d.rms_ba},
                     {"max_a_to_b", d.max_ab},    {"max_b_to_a", d.max_ba},
                     {"diagonal", d.diagonal}};
}

void to_json(nlohmann::json& j, const WatermarkOptions& o) {
  j = nlohmann::json{
      {"scheme", to_string(o.scheme)}, {"wavelet", to_string(o.wavelet)}, {"strength", o.strength_percent}};
}

nlohmann::json basis_json(const PreparedModel& model) {
  nlohmann::json j = {{"kind", to_string(model.basis)},
                      {"reason", model.basis_reason},
                      {"small_components", model.report.small_components}};
  if (model.spherical()) {
    j["grid"] = {{"base", to_string(model.base)}, {"level", model.level()}, {"samples", model.sample_count()}};
    if (model.basis == MeshBasis::sphere_filled)
      j["filling"] = {{"vertices", model.filled.V.rows() - model.mesh.V.rows()},
                      {"faces", model.filled.F.rows() - model.mesh.F.rows()}};
  } else {
    const BumpBasis& b = *model.bumps;
    j["bumps"] = b.values.cols();
    j["bands"] = b.bands();
    j["band_support_vertices"] = b.band_support;
    j["marked_components"] = b.marked_components;
    j["skipped_components"] = b.skipped_components;
    j["skipped_vertices"] = b.skipped_vertices;
  }
  return j;
}

nlohmann::json embed_report(const PreparedModel& model, const WatermarkOptions& options, const EmbedResult& result,
                            const SurfaceDistance& distortion) {
  nlohmann::json j;
  j["parameters"] = options;
  j["parameters"]["base"] = to_string(model.base);
  j["basis"] = basis_json(model);
  if (model.spherical())
    j["grid"] = {{"level", model.level()},
                 {"samples", model.sample_count()},
                 {"level_rule_error", model.sampling.error},
                 {"level_rule_reached_epsilon", model.sampling.reached_epsilon}};
  j["carriers"] = result.carriers;
  j["carrier_levels"] = result.carrier_levels;
  j["coded_bits"] = result.coded_bits;
  j["warnings"] = result.warnings;
  j["distortion"] = {{"mrms", distortion.mrms_relative()},
                     {"hausdorff", distortion.hausdorff_relative()},
                     {"rms_displacement", result.rms_displacement},
                     {"max_displacement", result.max_displacement}};
  nlohmann::json seconds = result.seconds;
  seconds["prepare"] = model.prepare_seconds;
  if (model.spherical()) seconds["parameterization"] = model.param.seconds;
  j["seconds"] = seconds;
  return j;
}

void to_json(nlohmann::json& j, const Similarity& s) {
  nlohmann::json rotation = nlohmann::json::array();
  for (int r = 0; r < 3; ++r) rotation.push_back({s.R(r, 0), s.R(r, 1), s.R(r, 2)});
  j = {{"rotation", rotation}, {"scale", s.scale}, {"translation", {s.t.x(), s.t.y(), s.t.z()}}};
}

void from_json(const nlohmann::json& j, Similarity& s) {
  const nlohmann::json& rotation = j.at("rotation");
  const nlohmann::json& translation = j.at("translation");
  if (!rotation.is_array() || rotation.size() != 3 || !translation.is_array() || translation.size() != 3)
    throw std::invalid_argument("a transform has a 3x3 rotation and a translation of 3");
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) s.R(r, c) = rotation.at(r).at(c).get<double>();
  s.scale = j.at("scale").get<double>();
  for (int k = 0; k < 3; ++k) s.t(k) = translation.at(k).get<double>();
}

void to_json(nlohmann::json& j, const DetectResult& r) {
  j = nlohmann::json{{"detected", r.detected},
                     {"payload", r.payload ? nlohmann::json(hex_from_bits(*r.payload)) : nlohmann::json(nullptr)},
                     {"decoded", hex_from_bits(r.decoded)},
                     {"checksum_ok", r.checksum_ok},
                     {"bits", r.decoded.size()},
                     {"ber", r.ber ? nlohmann::json(*r.ber) : nlohmann::json(nullptr)},
                     {"p_value", r.p_value},
                     {"log10_p_value", r.log10_p_value},
                     {"evidence", r.evidence},
                     {"blind_log10_p_value", r.blind_log10_p_value},
                     {"z_score", r.z_score},
                     {"correlation", r.correlation},
                     {"alignment",
                      {{"rms", r.alignment.rms},
                       {"rigid_rms", r.alignment.rigid_rms},
                       {"non_rigid", !r.alignment.deformation.identity()},
                       {"overlap", r.alignment.overlap},
                       {"quality", r.alignment.poor() ? "poor" : "good"},
                       {"scale", r.alignment.transform.scale},
                       {"iterations", r.alignment.iterations},
                       {"start", r.alignment.start},
                       {"mirrored", r.alignment.mirrored},
                       {"candidates", r.alignment_candidates},
                       {"transform", r.alignment.transform}}},
                     {"samples", r.samples},
                     {"missing", r.missing},
                     {"seconds", r.seconds}};
  if (r.expected_p_value) j["expected_p_value"] = *r.expected_p_value;
  if (r.expected_log10_p_value) j["expected_log10_p_value"] = *r.expected_log10_p_value;
  if (r.raw_bit_error_rate >= 0) j["raw_bit_error_rate"] = r.raw_bit_error_rate;
}

}  // namespace meshmark

namespace meshmark {

void to_json(nlohmann::json& j, const DocumentPart& p) {
  j = {{"name", p.name},
       {"stored_vertices", p.stored_vertices},
       {"triangles", p.triangles},
       {"instances", p.instances},
       {"attributes", p.attributes}};
}

nlohmann::json document_json(const MeshDocument& document, const WeldedSurface& surface) {
  const Mesh scene = document.scene();
  return {{"format", to_string(document.format())},
          {"parts", document.parts()},
          {"companions", document.companions()},
          {"stored_vertices", document.slot_positions().rows()},
          {"triangles", document.slot_triangles().rows()},
          {"polygons_triangulated", document.polygons_triangulated()},
          {"scene", {{"vertices", scene.V.rows()}, {"triangles", scene.F.rows()}}},
          {"welded",
           {{"vertices", surface.mesh.V.rows()},
            {"triangles", surface.mesh.F.rows()},
            {"copies_joined", surface.welded_copies},
            {"collapsed_triangles", surface.collapsed_triangles},
            {"duplicate_triangles", surface.duplicate_triangles}}}};
}

void to_json(nlohmann::json& j, const CopyVerification& verification) {
  j = {{"skipped", verification.skipped},
       {"passed", !verification.skipped && verification.passed()},
       {"seconds", verification.seconds()},
       {"readings", nlohmann::json::array()}};
  for (const CopyReading& r : verification.readings)
    j["readings"].push_back({{"name", r.name},
                             {"passed", r.passed},
                             {"detected", r.detected},
                             {"payload_read", r.payload_read},
                             {"ber", r.ber},
                             {"log10_p_value", r.log10_p_value},
                             {"seconds", r.seconds}});
}

}  // namespace meshmark
