#pragma once
// One parser per format; read_mesh_from_memory dispatches to them.

#include <string_view>

#include "core/io/read_mesh.hpp"

namespace meshmark {

ReadResult read_obj(std::string_view bytes, const ReadOptions& options, std::string_view source);
ReadResult read_off(std::string_view bytes, const ReadOptions& options, std::string_view source);
ReadResult read_ply(std::string_view bytes, const ReadOptions& options, std::string_view source);
ReadResult read_stl(std::string_view bytes, const ReadOptions& options, std::string_view source);

}  // namespace meshmark
