#pragma once

#include <filesystem>
#include <string_view>

namespace meshmark {

/// Writes `bytes` to a temporary file beside `path`, fsyncs it, renames it over `path` and
/// fsyncs the directory: afterwards the file is whole and durable, or unchanged.
/// Throws std::runtime_error naming the path and the system error.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace meshmark
