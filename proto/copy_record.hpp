#pragma once
// The record of one marked copy: what detection needs to read it (scheme, wavelet, grid base,
// payload and its length, strength) and which original it was made from, with that original
// itself as it was prepared. `meshmark embed` writes it in the records folder, never beside the
// copy; `meshmark detect --record FILE` reads it, so a
// copy made with non-default settings is read without repeating them. The daemon keeps the same
// facts per embedding in its store.

#include <nlohmann/json.hpp>

#include <string>

namespace meshmark {

inline constexpr int kCopyRecordVersion = 1;

struct CopyRecord {
  std::string payload;  ///< hex
  std::string scheme, wavelet, base;
  double strength = 0;          ///< percent of the bbox diagonal
  std::string original_digest;  ///< mesh_digest of the welded original surface
  long long original_vertices = 0, original_faces = 0;
  std::string original_file, copy_file, created_at;
  /// Beside the record (names relative to it): the welded original surface as prepared (binary
  /// PLY, doubles) and its prepared model, so that detection reads against exactly the original
  /// the copy was made from, whatever happened to the original's file since. Empty: none.
  std::string stored_original, stored_prepared;
  /// Whether the copy was read back before it was handed out (false: embed --no-verify).
  bool verified = true;
  std::string recipient = {};  ///< who received the copy (embed --recipients); empty: not said
};

nlohmann::json to_json(const CopyRecord& r);
/// Throws std::invalid_argument saying what is wrong (not a record, a newer version, a field).
CopyRecord copy_record_from_json(const nlohmann::json& j);

}  // namespace meshmark
