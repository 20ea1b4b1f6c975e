#pragma once
// Reading the records `embed` writes beside each copy (proto/copy_record.hpp), and the original
// they store, for `detect --record` and `trace`.

#include <string>

#include "core/watermark/prepared_model.hpp"
#include "proto/copy_record.hpp"

namespace meshmark::cli {

/// Throws std::invalid_argument naming the file when it is not a record.
CopyRecord read_copy_record(const std::string& path);

/// The original a record stores beside it, prepared as it was when the copy was made. Throws
/// std::invalid_argument when it does not load.
PreparedModel load_recorded_original(const std::string& record_path, const CopyRecord& record,
                                     const JobControl* control);

}  // namespace meshmark::cli
