// The PLY reader on arbitrary bytes: it returns a mesh or throws MeshIoError, within limits.

#include "core/io/read_mesh.hpp"
#include "tests/fuzz/fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  meshmark::ReadOptions options;
  options.max_vertices = 100000;
  options.max_faces = 200000;
  try {
    const auto r = meshmark::read_mesh_from_memory(as_text(data, size), meshmark::MeshFormat::ply, options, "fuzz");
    // What was read is a mesh the pipeline may trust: indices in range, finite coordinates.
    if (r.mesh.F.size() > 0 && (r.mesh.F.minCoeff() < 0 || r.mesh.F.maxCoeff() >= r.mesh.V.rows())) __builtin_trap();
    if (!r.mesh.V.allFinite()) __builtin_trap();
  } catch (const meshmark::MeshIoError&) {
  }
  return 0;
}
