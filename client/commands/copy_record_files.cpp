#include "client/commands/copy_record_files.hpp"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "core/io/mesh_document.hpp"
#include "core/io/read_mesh.hpp"
#include "core/watermark/prepared_model_io.hpp"

namespace meshmark::cli {

std::filesystem::path default_records_folder() {
  if (const char* set = std::getenv("MESHMARK_RECORDS"); set && *set) return set;
  if (const char* data = std::getenv("XDG_DATA_HOME"); data && *data)
    return std::filesystem::path(data) / "meshmark" / "records";
  const char* home = std::getenv("HOME");
  return std::filesystem::path(home && *home ? home : ".") / ".local" / "share" / "meshmark" / "records";
}

std::filesystem::path record_path_in(const std::filesystem::path& folder, const std::filesystem::path& copy_file,
                                     const std::string& payload_hex) {
  return folder / (copy_file.filename().string() + "-" + payload_hex + ".record.json");
}

CopyRecord read_copy_record(const std::string& path) {
  const std::string text = read_file_bytes(path, 1u << 20);
  const auto j = nlohmann::json::parse(text, nullptr, false);
  try {
    return copy_record_from_json(j);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(path + ": " + e.what());
  }
}

PreparedModel load_recorded_original(const std::string& record_path, const CopyRecord& record,
                                     const JobControl* control) {
  const std::filesystem::path folder = std::filesystem::path(record_path).parent_path();
  const Mesh mesh = read_mesh(folder / record.stored_original).mesh;
  try {
    return deserialize_prepared_model(read_file_bytes(folder / record.stored_prepared, 1u << 31), mesh, nullptr,
                                      control);
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(record_path + ": the stored original does not load (" + e.what() + ")");
  }
}

}  // namespace meshmark::cli
