#include "server/store/orphan_sweep.hpp"

#include <map>
#include <string>
#include <vector>

#include "server/store/blob_keys.hpp"

namespace meshmark::server {

namespace {

// The record id a key "FOLDER/ID/NAME" belongs to; empty for a key of another shape.
std::string record_id_of(const std::string& key, const std::string& folder) {
  const std::size_t start = folder.size() + 1;
  const std::size_t slash = key.find('/', start);
  if (key.compare(0, start, folder + "/") != 0 || slash == std::string::npos || slash == start) return {};
  return key.substr(start, slash - start);
}

}  // namespace

SweepReport sweep_orphan_blobs(Store& store, BlobStore& blobs, const Clock& clock, std::chrono::seconds grace) {
  SweepReport report;
  const auto cutoff = clock.now() - grace;
  for (const std::string folder : {kModelsFolder, kJobsFolder}) {
    std::map<std::string, bool> recorded;  // id → has a row, asked once per sweep
    const auto has_record = [&](const std::string& id) {
      const auto known = recorded.find(id);
      if (known != recorded.end()) return known->second;
      const bool found = folder == kModelsFolder ? store.model_by_id(id).has_value() : store.job_by_id(id).has_value();
      return recorded[id] = found;
    };
    std::vector<std::string> orphans;  // removed after the listing, which may not see its folder change
    blobs.list(folder, [&](const StoredBlob& blob) {
      ++report.examined;
      const std::string id = record_id_of(blob.key, folder);
      if (!id.empty() && blob.modified < cutoff && !has_record(id)) orphans.push_back(blob.key);
    });
    for (const std::string& key : orphans) blobs.remove_prefix(key);
    report.removed += orphans.size();
  }
  return report;
}

}  // namespace meshmark::server
