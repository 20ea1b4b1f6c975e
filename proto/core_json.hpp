#pragma once
// JSON forms of core results. The keys are part of the public contract (CLI --json and the
// HTTP API): add keys freely, never rename or remove one.

#include <nlohmann/json.hpp>

#include "core/mesh/similarity.hpp"
#include "core/mesh/validate_mesh.hpp"

namespace meshmark {

void to_json(nlohmann::json& j, const MeshReport& report);

}  // namespace meshmark

#include "core/param/sphere_param.hpp"

namespace meshmark {

void to_json(nlohmann::json& j, const AreaDistortion& d);
/// The parameterization's summary (without the per-vertex map).
void to_json(nlohmann::json& j, const SphereParam& p);

}  // namespace meshmark

#include "core/metrics/compare_meshes.hpp"
#include "core/watermark/watermark.hpp"

namespace meshmark {

/// The basis that carries the watermark: its kind, why, and its size (grid, or bumps and bands).
nlohmann::json basis_json(const PreparedModel& model);

/// What `embed --json` and the embed job report: parameters, grid, carriers, distortion, seconds.
nlohmann::json embed_report(const PreparedModel& model, const WatermarkOptions& options, const EmbedResult& result,
                            const SurfaceDistance& distortion);

void to_json(nlohmann::json& j, const WatermarkOptions& options);
void to_json(nlohmann::json& j, const SurfaceDistance& distance);
/// The alignment's pose, suspect coordinates → original's: {"rotation": 3 rows, "scale", "translation"}.
void to_json(nlohmann::json& j, const Similarity& s);
void from_json(const nlohmann::json& j, Similarity& s);
void to_json(nlohmann::json& j, const DetectResult& result);

}  // namespace meshmark

#include "core/io/mesh_document.hpp"
#include "core/mesh/weld_positions.hpp"

namespace meshmark {

void to_json(nlohmann::json& j, const DocumentPart& part);
/// What a file holds (format, parts, stored vertices, the scene) and the surface welded from it.
nlohmann::json document_json(const MeshDocument& document, const WeldedSurface& surface);

}  // namespace meshmark

#include "core/verification/verify_copy.hpp"

namespace meshmark {

/// The self-check of a marked copy, as embed --json and the embed job report it.
void to_json(nlohmann::json& j, const CopyVerification& verification);

}  // namespace meshmark
