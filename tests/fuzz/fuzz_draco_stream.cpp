// A Draco stream on arbitrary bytes, as a glTF primitive holds it: its declared size read ahead
// and checked against small limits before libdraco decodes it; what decodes is a mesh the
// pipeline may trust, within those limits. Only MeshIoError escapes.

#include "core/io/draco_primitive.hpp"
#include "core/io/mesh_io_error.hpp"
#include "tests/fuzz/fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const meshmark::DracoPrimitive primitive(as_text(data, size), 0, {100'000, 200'000});
    const auto& faces = primitive.faces();
    if (faces.size() > 0 && (faces.minCoeff() < 0 || faces.maxCoeff() >= primitive.positions().rows()))
      __builtin_trap();
  } catch (const meshmark::MeshIoError&) {
  }
  return 0;
}
