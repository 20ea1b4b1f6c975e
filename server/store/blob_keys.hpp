#pragma once
// Where each of the daemon's files lives in the blob store. Every key is under a model's or a
// job's folder, named by the record's id: a blob whose record is gone is an orphan
// (orphan_sweep.hpp). Ids are never reused, so a key is written once (an embed job tried again
// writes the same verified copy).

#include <string>

namespace meshmark::server {

inline constexpr const char* kModelsFolder = "models";
inline constexpr const char* kJobsFolder = "jobs";

/// A model's folder, and the files in it.
std::string model_prefix(const std::string& model_id);
/// The model's surface (welded, binary PLY): what it is prepared from.
std::string original_key(const std::string& model_id);
/// The file as uploaded, byte for byte: what marked copies are written from. (Absent for models
/// uploaded before the daemon kept it: their copies are written from the surface.)
std::string upload_key(const std::string& model_id);
std::string prepared_key(const std::string& model_id);

/// A job's folder, and the files in it.
std::string job_prefix(const std::string& job_id);
std::string suspect_key(const std::string& job_id);
std::string output_key(const std::string& job_id, const std::string& format);

}  // namespace meshmark::server
