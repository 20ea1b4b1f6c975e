#pragma once
// Where `embed` keeps the records of the copies it made (proto/copy_record.hpp) and the originals
// they store — never in the copy's folder, which holds only what is handed out — and reading them
// back for `detect --record` and `trace`.

#include <filesystem>
#include <string>

#include "core/watermark/prepared_model.hpp"
#include "proto/copy_record.hpp"

namespace meshmark::cli {

/// $MESHMARK_RECORDS, else ${XDG_DATA_HOME:-$HOME/.local/share}/meshmark/records.
std::filesystem::path default_records_folder();

/// The record of the copy `copy_file` with `payload_hex` in `folder`: one per copy name and payload.
std::filesystem::path record_path_in(const std::filesystem::path& folder, const std::filesystem::path& copy_file,
                                     const std::string& payload_hex);

/// Throws std::invalid_argument naming the file when it is not a record.
CopyRecord read_copy_record(const std::string& path);

/// The original a record stores beside it, prepared as it was when the copy was made. Throws
/// std::invalid_argument when it does not load.
PreparedModel load_recorded_original(const std::string& record_path, const CopyRecord& record,
                                     const JobControl* control);

}  // namespace meshmark::cli
