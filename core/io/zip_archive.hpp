#pragma once
// A ZIP archive (the container of a 3MF package) read, and written again with new contents for
// some entries and every other byte copied: the other entries' headers and data, the central
// directory's records (only sizes, checksums and offsets patched) and the archive comment.
// Stored and deflated entries; ZIP64, encrypted and multi-disk archives are refused.

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace meshmark {

struct ZipEntry {
  std::string name;
  std::uint16_t flags = 0;
  std::uint16_t method = 0;  ///< 0 stored, 8 deflated
  std::uint32_t crc = 0;
  std::uint32_t compressed_size = 0;
  std::uint32_t size = 0;          ///< uncompressed
  std::size_t local_header = 0;    ///< offset of its local header
  std::size_t data = 0;            ///< offset of its (compressed) data
  std::size_t central_record = 0;  ///< offset of its central directory record
};

/// Deflate reaches about 1000:1 on repeated bytes; meshes and their textures inflate far less.
inline constexpr std::size_t kMaxInflateRatio = 100;
inline constexpr std::size_t kMinInflateBudget = std::size_t{64} << 20;

class ZipArchive {
 public:
  /// Reads the central directory. Entries larger than `max_entry_bytes` uncompressed can be
  /// listed but not extracted, and every extraction together may inflate no more than that, nor
  /// more than kMaxInflateRatio times the archive (at least kMinInflateBudget): MeshLimitError.
  /// Throws MeshIoError naming `source`.
  ZipArchive(std::string bytes, std::size_t max_entry_bytes, std::string source);

  const std::vector<ZipEntry>& entries() const { return entries_; }
  /// The archive as read.
  const std::string& bytes() const { return bytes_; }
  /// The entry of that name (ASCII case-insensitive, as OPC packages compare names); null if none.
  const ZipEntry* find(std::string_view name) const;
  /// Its uncompressed bytes, checked against its size and CRC-32; counted against the budget.
  std::string extract(const ZipEntry& entry) const;
  /// The archive with the entries named in `contents` holding those bytes (compressed as they
  /// were), every other byte as read.
  std::string with_contents(const std::map<std::string, std::string>& contents) const;

 private:
  [[noreturn]] void fail(const std::string& what) const;
  void read_central_directory();

  std::string bytes_;
  std::size_t max_entry_bytes_;
  std::size_t inflate_budget_ = 0;
  mutable std::size_t extracted_bytes_ = 0;  // by extract(), against inflate_budget_
  std::string source_;
  std::vector<ZipEntry> entries_;
  std::size_t central_directory_ = 0;  // offset
  std::size_t end_record_ = 0;         // offset of the end-of-central-directory record
};

/// A new archive of `files` (name, bytes), in that order, each stored uncompressed (meshes and
/// textures barely compress, and a stored entry reads back without inflating). Throws
/// MeshIoError for an empty, absolute or climbing name, a repeated one, or an archive that
/// would need ZIP64.
std::string write_zip(const std::vector<std::pair<std::string, std::string>>& files);

}  // namespace meshmark
