#pragma once
// The API's resource paths, built in one place for the daemon (Location headers, links in
// views) and the client.

#include <string>

namespace meshmark::links {

inline std::string owners() { return "/v1/owners"; }
inline std::string owner(const std::string& id) { return owners() + "/" + id; }
inline std::string owner_key(const std::string& id) { return owner(id) + "/key"; }
inline std::string owner_watermark_key(const std::string& id) { return owner(id) + "/watermark-key"; }
inline std::string models() { return "/v1/models"; }
inline std::string model(const std::string& id) { return "/v1/models/" + id; }
inline std::string model_embed(const std::string& id) { return model(id) + "/embed"; }
inline std::string model_detect(const std::string& id) { return model(id) + "/detect"; }
inline std::string model_embeddings(const std::string& id) { return model(id) + "/embeddings"; }
inline std::string model_detections(const std::string& id) { return model(id) + "/detections"; }
inline std::string model_copies_zip(const std::string& id) { return model(id) + "/copies.zip"; }
inline std::string embeddings_export() { return "/v1/embeddings"; }
inline std::string library_detect() { return "/v1/detect"; }
inline std::string job(const std::string& id) { return "/v1/jobs/" + id; }
inline std::string job_result(const std::string& id) { return job(id) + "/result"; }
inline std::string job_report(const std::string& id) { return job(id) + "/report"; }
inline std::string job_preview(const std::string& id) { return job(id) + "/preview"; }
inline std::string model_preview(const std::string& id) { return model(id) + "/preview"; }

}  // namespace meshmark::links
