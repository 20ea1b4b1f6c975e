#include "client/commands/recipients.hpp"

#include <set>
#include <sstream>
#include <stdexcept>

#include "core/io/mesh_document.hpp"

namespace meshmark::cli {

std::vector<std::string> read_recipients(const std::vector<std::string>& given, const std::string& file) {
  std::vector<std::string> names = given;
  if (!file.empty()) {
    std::istringstream lines(read_file_bytes(file, 16u << 20));
    bool first = true;
    for (std::string line; std::getline(lines, line); first = false) {
      std::string name = line.substr(0, line.find(','));
      name.erase(0, name.find_first_not_of(" \t\r\""));
      name.erase(name.find_last_not_of(" \t\r\"") + 1);
      const bool header = first && name.rfind("recipient", 0) == 0;
      if (!name.empty() && name.front() != '#' && !header) names.push_back(name);
    }
  }
  std::set<std::string> seen;
  for (const std::string& n : names)
    if (!seen.insert(n).second) throw std::invalid_argument("recipient '" + n + "' is named twice");
  if (names.empty()) throw std::invalid_argument("--recipients and --recipients-file name nobody");
  return names;
}

}  // namespace meshmark::cli
