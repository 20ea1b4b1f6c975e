// meshmark info MESH [--json]: what the file holds (parts, attributes, instances) and the report
// on the surface welded from it; exit 0 when that surface can be watermarked.

#include <cstdio>
#include <iostream>

#include "client/commands/commands.hpp"
#include "core/io/document_surface.hpp"
#include "core/mesh/validate_mesh.hpp"
#include "proto/core_json.hpp"

namespace meshmark::cli {

namespace {

void print_document(const MeshDocument& d, const WeldedSurface& surface) {
  std::printf("  format                %s\n", to_string(d.format()).c_str());
  for (const DocumentPart& p : d.parts()) {
    std::printf("  part                  %s: %zu vertices, %zu triangles", p.name.c_str(), p.stored_vertices,
                p.triangles);
    if (p.instances != 1) std::printf(", %zu instances", p.instances);
    std::printf("\n");
    for (const std::string& a : p.attributes) std::printf("                          %s\n", a.c_str());
  }
  for (const std::string& c : d.companions()) std::printf("  companion file        %s\n", c.c_str());
  std::printf("  welded surface        %zu stored vertices -> %lld (%zu copies at a shared position joined",
              static_cast<std::size_t>(d.slot_positions().rows()), static_cast<long long>(surface.mesh.V.rows()),
              surface.welded_copies);
  if (surface.collapsed_triangles) std::printf(", %zu triangles collapsed", surface.collapsed_triangles);
  if (surface.duplicate_triangles)
    std::printf(", %zu triangles over the vertices of another left out (double-sided or stored twice)",
                surface.duplicate_triangles);
  std::printf(")\n");
}

void print_text(const std::string& path, const MeshReport& r, std::size_t triangulated) {
  std::printf("%s\n", path.c_str());
  std::printf("  vertices              %zu\n  faces                 %zu\n", r.vertices, r.faces);
  if (triangulated) std::printf("  polygons triangulated %zu\n", triangulated);
  std::printf("  components            %zu\n", r.components);
  std::printf("  boundary edges        %zu (%zu loops)\n", r.boundary_edges, r.boundary_loops);
  std::printf("  non-manifold edges    %zu\n  non-manifold vertices %zu\n", r.nonmanifold_edges,
              r.nonmanifold_vertices);
  std::printf("  zero-area faces       %zu\n  duplicate vertices    %zu\n  isolated vertices     %zu\n",
              r.zero_area_faces, r.duplicate_vertices, r.isolated_vertices);
  std::printf("  euler characteristic  %lld\n", r.euler_characteristic);
  std::printf("  genus                 %s\n", r.genus ? std::to_string(*r.genus).c_str() : "undefined");
  std::printf("  orientation           %s\n", to_string(r.orientation).c_str());
  std::printf("  bbox diagonal         %.6g\n", r.bbox_diagonal);
  std::printf("  closed genus 0        %s\n", r.closed_genus_zero ? "yes" : "no");
  std::printf("  can be watermarked    %s\n", r.valid ? "yes" : "no");
  if (r.valid) std::printf("  watermark basis       %s: %s\n", to_string(r.basis).c_str(), r.basis_reason.c_str());
  if (r.small_components)
    std::printf("  left unmarked         %zu component(s) below %zu vertices\n", r.small_components,
                r.marked_component_floor);
  for (const auto& p : r.problems) std::printf("  problem: %s\n", p.c_str());
  if (r.basis != MeshBasis::sphere)
    for (const auto& p : r.sphere_problems) std::printf("  not a sphere: %s\n", p.c_str());
  for (const auto& w : r.warnings) std::printf("  warning: %s\n", w.c_str());
}

}  // namespace

void register_info(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("info", "Report a mesh's topology and whether it can be watermarked");
  auto path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("mesh", *path, "Mesh file (.obj, .off, .ply, .stl, .glb, .gltf, .3mf)")->required();
  cmd->add_flag("--json", *json, "Print JSON");
  cmd->callback([&action, path, json] {
    action = [path, json] {
      const auto document = read_document_file(*path);
      const WeldedSurface surface = document_surface(*document);
      const MeshReport report = validate_mesh(surface.mesh);
      if (*json) {
        nlohmann::json j = report;
        j["file"] = *path;
        j["polygons_triangulated"] = document->polygons_triangulated();
        j["document"] = document_json(*document, surface);
        std::cout << j.dump(2) << "\n";
      } else {
        print_text(*path, report, document->polygons_triangulated());
        print_document(*document, surface);
      }
      return report.valid ? kExitOk : kExitRefused;
    };
  });
}

}  // namespace meshmark::cli
