// A ZIP archive on arbitrary bytes: read, every entry extracted (each, and all together, within
// the inflate budget), then written again with one entry replaced; only MeshIoError escapes, and
// an extraction is never larger than its entry says.

#include "core/io/mesh_io_error.hpp"
#include "core/io/zip_archive.hpp"
#include "tests/fuzz/fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const meshmark::ZipArchive archive(std::string(as_text(data, size)), std::size_t{1} << 20, "fuzz");
    for (const meshmark::ZipEntry& entry : archive.entries()) {
      try {
        if (archive.extract(entry).size() != entry.size) __builtin_trap();
      } catch (const meshmark::MeshIoError&) {
      }
    }
    if (!archive.entries().empty()) archive.with_contents({{archive.entries().front().name, "replaced"}});
  } catch (const meshmark::MeshIoError&) {
  }
  return 0;
}
