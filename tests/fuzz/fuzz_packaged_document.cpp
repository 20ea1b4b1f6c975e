// A packaged document (a ZIP of a glTF or an OBJ with its companion files, or a 3MF) on arbitrary
// bytes, under small limits so that amplification shows: the first byte picks the format, the
// rest is the file. It reads or is refused with MeshIoError; one that reads writes itself back
// when nothing moved: byte for byte alone, as a ZIP that reads to the same positions (its
// entries are compressed again); nothing else may escape, crash or trip a sanitizer.

#include <optional>

#include "core/io/mesh_io_error.hpp"
#include "core/io/packaged_document.hpp"
#include "tests/fuzz/fuzz_document_limits.hpp"
#include "tests/fuzz/fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace meshmark;
  if (size < 1) return 0;
  constexpr MeshFormat kFormats[] = {MeshFormat::gltf, MeshFormat::obj, MeshFormat::threemf, MeshFormat::glb};
  const MeshFormat format = kFormats[data[0] % 4];
  const std::string bytes(as_text(data + 1, size - 1));
  const DocumentReadOptions options = fuzz_document_options();
  std::optional<PackagedDocument> package;
  try {
    package.emplace(bytes, format, options, "fuzz");
  } catch (const MeshIoError&) {
    return 0;
  }
  const Mesh scene = package->document().scene();
  if (scene.F.size() > 0 && (scene.F.minCoeff() < 0 || scene.F.maxCoeff() >= scene.V.rows())) __builtin_trap();
  const Vertices& positions = package->document().slot_positions();
  const std::string written = package->write(positions, {});
  if (!package->zipped()) {
    if (written != bytes) __builtin_trap();
    return 0;
  }
  try {
    const PackagedDocument again(written, format, options, "fuzz rewritten");
    if (again.document().slot_positions() != positions) __builtin_trap();
  } catch (const MeshLimitError&) {
    // compressed again, the archive may be smaller: the inflate budget is a ratio to its size
  } catch (const MeshIoError&) {
    __builtin_trap();
  }
  return 0;
}
