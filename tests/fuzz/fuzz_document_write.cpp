// Every document reader and writer on arbitrary bytes. The first byte picks the format (obj, off,
// ply, stl, glb, gltf, 3mf), the rest is the file. A file that reads must write back byte for
// byte when nothing moved, and, with every slot moved, write a file that reads again with as
// many slots (or refuse with MeshIoError); nothing else may escape, crash or trip a sanitizer.

#include "core/io/mesh_document.hpp"
#include "core/io/mesh_io_error.hpp"
#include "tests/fuzz/fuzz_document_limits.hpp"
#include "tests/fuzz/fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace meshmark;
  if (size < 1) return 0;
  constexpr MeshFormat kFormats[] = {MeshFormat::obj, MeshFormat::off,  MeshFormat::ply,    MeshFormat::stl,
                                     MeshFormat::glb, MeshFormat::gltf, MeshFormat::threemf};
  const MeshFormat format = kFormats[data[0] % 7];
  const std::string bytes(as_text(data + 1, size - 1));
  const DocumentReadOptions options = fuzz_document_options();
  std::unique_ptr<MeshDocument> doc;
  try {
    doc = read_document(bytes, format, options, "fuzz");
  } catch (const MeshIoError&) {
    return 0;
  }
  const Mesh scene = doc->scene();
  if (scene.F.size() > 0 && (scene.F.minCoeff() < 0 || scene.F.maxCoeff() >= scene.V.rows())) __builtin_trap();
  if (!scene.V.allFinite()) __builtin_trap();
  const DocumentFiles same = doc->write(doc->slot_positions(), {});
  if (same.size() != 1 || same.at("") != bytes) __builtin_trap();
  // Every slot moved by the same small step (a thousandth of the extent), far from the limits.
  Vertices moved = doc->slot_positions();
  const double extent = (moved.colwise().maxCoeff() - moved.colwise().minCoeff()).maxCoeff();
  if (!(extent > 0) || moved.cwiseAbs().maxCoeff() > 1e20) return 0;
  moved.array() += 1e-3 * extent;
  DocumentFiles files;
  try {
    files = doc->write(moved, {});
  } catch (const MeshIoError&) {
    return 0;  // e.g. a quantized type that cannot hold the moved positions
  }
  DocumentReadOptions again = options;
  again.companion = [&files](const std::string& uri) {
    if (auto it = files.find(uri); it != files.end()) return it->second;
    throw MeshIoError("no companion " + uri);
  };
  try {
    const auto back = read_document(files.at(""), format, again, "fuzz rewritten");
    // (STL numbers its slots by welding corners: 32-bit rounding may join or part some.)
    if (format != MeshFormat::stl && back->slot_positions().rows() != moved.rows()) __builtin_trap();
  } catch (const MeshIoError&) {
    // What we wrote must read; but STL welds corners by position, and moved corners rounded to
    // 32 bits may fall together until no facet is left.
    if (format != MeshFormat::stl) __builtin_trap();
  }
  return 0;
}
