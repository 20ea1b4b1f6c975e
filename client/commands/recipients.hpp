#pragma once
// Who receives copies, as a studio lists them: names on the command line and in a file (one per
// line, or a CSV whose first column is the name).

#include <string>
#include <vector>

namespace meshmark::cli {

/// `given`, then the names in `file` (if any): a header "recipient…" and lines starting with #
/// skipped. Throws std::invalid_argument for a name given twice or no name at all.
std::vector<std::string> read_recipients(const std::vector<std::string>& given, const std::string& file);

}  // namespace meshmark::cli
