#include "client/commands/upload_package.hpp"

#include <cstdio>
#include <optional>
#include <stdexcept>

#include "core/io/mesh_document.hpp"
#include "core/io/mesh_io_error.hpp"
#include "core/io/zip_archive.hpp"

namespace meshmark::cli {

namespace {

constexpr std::size_t kMaxUploadFile = std::size_t{1} << 30;

std::optional<MeshFormat> format_of_name(const std::filesystem::path& name) {
  try {
    return mesh_format_from_path(name);
  } catch (const MeshIoError&) {
    return std::nullopt;
  }
}

// A ZIP's format: from its name (chair.gltf.zip), else from the one mesh file it holds.
MeshFormat zip_format(const std::filesystem::path& file, const std::string& bytes) {
  if (const auto named = format_of_name(file.stem())) return *named;
  const ZipArchive zip(bytes, kMaxUploadFile, file.string());
  std::vector<std::string> meshes;
  std::optional<MeshFormat> format;
  for (const ZipEntry& e : zip.entries())
    if (const auto f = format_of_name(e.name); f && *f != MeshFormat::threemf) {
      meshes.push_back(e.name);
      format = f;
    }
  if (meshes.size() == 1) return *format;
  if (meshes.empty()) throw std::runtime_error(file.string() + " holds no mesh file (.gltf, .obj, .ply, …)");
  std::string names;
  for (const std::string& m : meshes) names += (names.empty() ? "" : ", ") + m;
  throw std::runtime_error(file.string() + " holds several mesh files (" + names + "): zip one with its companions");
}

// A companion's place in the archive: its URI as a relative path ("" when it would leave the folder).
std::string entry_name(const std::string& uri) {
  std::string path = percent_decoded(uri);
  if (path.empty() || path.front() == '/' || path.find("..") != std::string::npos) return {};
  return path;
}

}  // namespace

UploadPackage package_for_upload(const std::filesystem::path& file) {
  UploadPackage package;
  package.bytes = read_file_bytes(file, kMaxUploadFile);
  if (file.extension() == ".zip") {
    package.format = zip_format(file, package.bytes);
    return package;
  }
  package.format = mesh_format_from_path(file);
  if (package.format != MeshFormat::gltf && package.format != MeshFormat::obj) return package;
  std::vector<std::pair<std::string, std::string>> files = {{file.filename().string(), package.bytes}};
  const auto document = read_document_file(file);
  for (const std::string& uri : document->companions()) {
    const std::string name = entry_name(uri);
    const std::filesystem::path beside = file.parent_path() / name;
    if (name.empty() || !std::filesystem::is_regular_file(beside)) {
      package.missing.push_back(uri);
      continue;
    }
    files.emplace_back(name, read_file_bytes(beside, kMaxUploadFile));
    package.packed.push_back(name);
  }
  if (!package.packed.empty()) package.bytes = write_zip(files);
  return package;
}

void warn_missing_companions(const std::filesystem::path& file, const UploadPackage& package) {
  for (const std::string& uri : package.missing)
    std::fprintf(stderr,
                 "meshmark: warning: %s refers to %s, which is not beside it: the daemon keeps the file without it, "
                 "and copies will refer to a file they do not contain\n",
                 file.filename().c_str(), uri.c_str());
}

}  // namespace meshmark::cli
