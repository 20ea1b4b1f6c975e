#include "core/verification/read_back.hpp"

#include "core/io/packaged_document.hpp"
#include "core/io/document_surface.hpp"

namespace meshmark {

Mesh read_back(const DocumentFiles& files, MeshFormat format,
               const std::function<std::string(const std::string& uri)>& unchanged, const ReadOptions& limits) {
  DocumentReadOptions options;
  options.limits = limits;
  options.for_writing = false;
  options.companion = [&](const std::string& uri) {
    auto written = files.find(uri);
    if (written == files.end()) written = files.find(percent_decoded(uri));
    return written != files.end() ? written->second : unchanged(uri);
  };
  return document_surface(*read_document(files.at(""), format, options, "the marked copy")).mesh;
}

Mesh read_back(const std::string& bytes, MeshFormat format, const ReadOptions& limits) {
  DocumentReadOptions options;
  options.limits = limits;
  options.for_writing = false;
  return document_surface(PackagedDocument(bytes, format, options, "the marked copy").document()).mesh;
}

}  // namespace meshmark
