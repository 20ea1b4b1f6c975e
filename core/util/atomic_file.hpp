#pragma once

#include <filesystem>
#include <string_view>

namespace meshmark {

/// The name of every temporary write_file_atomically makes begins so: one left by a crash is
/// recognised as a half-written file, never taken for a file.
inline constexpr std::string_view kAtomicTemporaryPrefix = ".tmp-";

/// Writes `bytes` to a temporary file beside `path`, fsyncs it, renames it over `path` and
/// fsyncs the directory: afterwards the file is whole and durable, or unchanged.
/// Throws std::system_error (its code the system error, e.g. ENOSPC) naming the path.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

/// fsync of a directory, so that entries added to it survive a power loss.
void fsync_directory(const std::filesystem::path& dir);

/// create_directories, with each parent fsynced after a child is made in it.
void create_directories_durably(const std::filesystem::path& dir);

}  // namespace meshmark
