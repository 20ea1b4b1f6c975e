#pragma once
// A mesh's validation report in a binary file, so that a stored prepared model loads without
// validating its mesh again (a third of loading a large one).

#include "core/mesh/validate_mesh.hpp"
#include "core/util/binary_io.hpp"

namespace meshmark {

void put_mesh_report(BinaryWriter& w, const MeshReport& m);

/// Throws std::runtime_error on a truncated or out-of-range report.
MeshReport get_mesh_report(BinaryReader& r);

}  // namespace meshmark
