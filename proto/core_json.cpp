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
      {"valid", r.valid},
      {"problems", r.problems},
      {"warnings", r.warnings},
  };
}

}  // namespace meshmark

namespace meshmark {

void to_json(nlohmann::json& j, const AreaDistortion& d) {
  j = nlohmann::json{{"min", d.min}, {"p05", d.p05}, {"median", d.median}, {"p95", d.p95}, {"max", d.max},
                     {"spread_p95_p05", d.p05 > 0 ? d.p95 / d.p05 : 0.0}};
}

void to_json(nlohmann::json& j, const SphereParam& p) {
  j = nlohmann::json{{"flipped_faces", p.flipped_faces},
                     {"degree", p.degree},
                     {"iterations", p.flow_iterations},
                     {"factorizations", p.factorizations},
                     {"flipped_before_repair", p.flipped_before_repair},
                     {"repair_rounds", p.repair_rounds},
                     {"flipped_input", p.flipped_input},
                     {"area_distortion", p.area_distortion},
                     {"conformal_area_distortion", p.conformal_area_distortion},
                     {"area_equalization",
                      {{"grid_levels", p.equalization.grid_levels},
                       {"steps", p.equalization.steps},
                       {"rejected_steps", p.equalization.rejected_steps},
                       {"density_spread_before", p.equalization.spread_before},
                       {"density_spread_after", p.equalization.spread_after},
                       {"seconds", p.equalize_seconds}}},
                     {"flow_seconds", p.flow_seconds},
                     {"seconds", p.seconds}};
}

}  // namespace meshmark
