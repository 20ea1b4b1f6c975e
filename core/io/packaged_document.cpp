#include "core/io/packaged_document.hpp"

#include <algorithm>

#include "core/io/mesh_io_error.hpp"

namespace meshmark {

namespace {

bool ends_with_extension(const std::string& name, const std::string& extension) {
  if (name.size() <= extension.size() + 1 || name[name.size() - extension.size() - 1] != '.') return false;
  return std::equal(extension.begin(), extension.end(), name.end() - static_cast<std::ptrdiff_t>(extension.size()),
                    [](char a, char b) {
                      return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
                    });
}

// A companion's name inside the archive: relative to the main file's folder, percent-decoded,
// and never outside the archive's root.
std::string entry_of(const std::string& folder, const std::string& uri, const std::string& source) {
  const std::string path = percent_decoded(uri);
  if (path.empty() || path.front() == '/' || path.find("..") != std::string::npos ||
      path.find(':') != std::string::npos)
    throw MeshIoError(source + ": the companion file '" + uri + "' is not a plain relative path beside the main file");
  return folder + path;
}

}  // namespace

bool looks_zipped(std::string_view bytes) {
  return bytes.size() >= 4 && bytes.substr(0, 4) == std::string_view("PK\x03\x04", 4);
}

PackagedDocument::PackagedDocument(std::string bytes, MeshFormat format, const DocumentReadOptions& options,
                                   const std::string& source)
    : source_(source) {
  if (format == MeshFormat::threemf || !looks_zipped(bytes)) {
    document_ = read_document(std::move(bytes), format, options, source);
    return;
  }
  zip_.emplace(std::move(bytes), options.limits.max_file_bytes, source);
  // The main file: the one entry with the format's extension (macOS resource forks aside).
  std::vector<std::string> candidates;
  for (const ZipEntry& e : zip_->entries())
    if (ends_with_extension(e.name, to_string(format)) && e.name.rfind("__MACOSX/", 0) != 0)
      candidates.push_back(e.name);
  if (candidates.empty()) throw MeshIoError(source + ": the ZIP archive holds no ." + to_string(format) + " file");
  if (candidates.size() > 1)
    throw MeshIoError(source + ": the ZIP archive holds " + std::to_string(candidates.size()) + " ." +
                      to_string(format) + " files ('" + candidates[0] + "', '" + candidates[1] +
                      "'); send one asset per upload");
  main_ = candidates.front();
  folder_ = main_.substr(0, main_.rfind('/') + 1);
  DocumentReadOptions with_companions = options;
  with_companions.companion = [this](const std::string& uri) {
    const ZipEntry* entry = zip_->find(entry_of(folder_, uri, source_));
    if (!entry) throw MeshIoError(source_ + ": the companion file '" + uri + "' is not in the ZIP archive");
    return zip_->extract(*entry);
  };
  document_ = read_document(zip_->extract(*zip_->find(main_)), format, with_companions, source + ": " + main_);
}

std::string PackagedDocument::write(const Vertices& positions, const NormalRotations& rotations) const {
  const DocumentFiles files = document_->write(positions, rotations);
  if (!zip_) {
    if (files.size() != 1) throw MeshIoError(source_ + ": changed companion files have no place outside a ZIP");
    return files.at("");
  }
  std::map<std::string, std::string> contents;
  for (const auto& [name, bytes] : files) {
    const std::string entry = name.empty() ? main_ : zip_->find(entry_of(folder_, name, source_))->name;
    contents[entry] = bytes;
  }
  return zip_->with_contents(contents);
}

}  // namespace meshmark
