#include "server/store/blob_keys.hpp"

namespace meshmark::server {

std::string model_prefix(const std::string& model_id) { return std::string(kModelsFolder) + "/" + model_id; }
std::string original_key(const std::string& model_id) { return model_prefix(model_id) + "/original.ply"; }
std::string upload_key(const std::string& model_id) { return model_prefix(model_id) + "/upload"; }
std::string prepared_key(const std::string& model_id) { return model_prefix(model_id) + "/prepared.bin"; }

std::string job_prefix(const std::string& job_id) { return std::string(kJobsFolder) + "/" + job_id; }
std::string suspect_key(const std::string& job_id) { return job_prefix(job_id) + "/suspect.ply"; }
std::string output_key(const std::string& job_id, const std::string& format) {
  return job_prefix(job_id) + "/output." + format;
}

}  // namespace meshmark::server
