#pragma once
// One document reader per format; read_document dispatches to them.

#include <memory>
#include <string>

#include "core/io/mesh_document.hpp"
#include "core/io/mesh_io_error.hpp"

namespace meshmark {

std::unique_ptr<MeshDocument> read_obj_document(std::string bytes, const DocumentReadOptions& options,
                                                const std::string& source);
std::unique_ptr<MeshDocument> read_off_document(std::string bytes, const DocumentReadOptions& options,
                                                const std::string& source);
std::unique_ptr<MeshDocument> read_ply_document(std::string bytes, const DocumentReadOptions& options,
                                                const std::string& source);
std::unique_ptr<MeshDocument> read_stl_document(std::string bytes, const DocumentReadOptions& options,
                                                const std::string& source);
std::unique_ptr<MeshDocument> read_gltf_document(std::string bytes, bool binary, const DocumentReadOptions& options,
                                                 const std::string& source);
std::unique_ptr<MeshDocument> read_3mf_document(std::string bytes, const DocumentReadOptions& options,
                                                const std::string& source);

}  // namespace meshmark
