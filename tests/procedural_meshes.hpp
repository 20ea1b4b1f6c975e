#pragma once
// Meshes the tests make themselves, so that every suite runs without the real meshes: the
// example shapes of core/mesh/example_shapes.hpp by name, made once per process, and written to
// files for the command line and the daemon.

#include <filesystem>
#include <string>

#include "core/mesh/example_shapes.hpp"
#include "core/mesh/mesh.hpp"

namespace meshmark::test {

// The generators live in core (core/mesh/example_shapes.hpp); the tests use them unqualified.
using meshmark::creature;
using meshmark::cube;
using meshmark::double_sided;
using meshmark::icosphere;
using meshmark::lumpy_torus;
using meshmark::pinched;
using meshmark::side_by_side;
using meshmark::torus;
using meshmark::with_holes;
using meshmark::wound_inward;

/// The named shapes the suites share, made once per process: the example shapes "creature"
/// (2,562 vertices), "creature_large" (10,242), "torus" (3,840), "creature_holes" and "parts";
/// and "creature_small" (creature(3): 642), "torus_small" (480), "pinched" (pinched()),
/// "creature_scan" (creature(4) remeshed: evenly spaced vertices on the surface, so that its
/// limbs hold many, as on a scan) and "creature_coarse" (the same with edges 1.5 times as long:
/// about 1,100), "creature_inward" (the creature with every face wound inward). Throws
/// std::invalid_argument for another name.
const Mesh& procedural_mesh(const std::string& shape);

/// A folder made once per process under the temporary directory (`prefix`-XXXXXX), removed when
/// the process exits.
std::filesystem::path process_temp_folder(const std::string& prefix);

/// procedural_mesh(shape) written once per process as `shape`.`extension` (obj, off, ply, stl)
/// into a temporary folder: for the command line and the daemon.
std::filesystem::path procedural_file(const std::string& shape, const std::string& extension = "obj");

}  // namespace meshmark::test
