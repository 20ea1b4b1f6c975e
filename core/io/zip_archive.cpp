#include "core/io/zip_archive.hpp"

#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <set>

#include "core/io/mesh_io_error.hpp"

namespace meshmark {

namespace {

constexpr std::uint32_t kLocalHeader = 0x04034b50, kCentralRecord = 0x02014b50, kEndRecord = 0x06054b50,
                        kDescriptor = 0x08074b50;
constexpr std::size_t kLocalFixed = 30, kCentralFixed = 46, kEndFixed = 22;

std::uint16_t get16(const std::string& b, std::size_t at) {
  return static_cast<std::uint16_t>(static_cast<unsigned char>(b[at]) | static_cast<unsigned char>(b[at + 1]) << 8);
}
std::uint32_t get32(const std::string& b, std::size_t at) {
  return get16(b, at) | static_cast<std::uint32_t>(get16(b, at + 2)) << 16;
}
void put32(std::string& b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + i] = static_cast<char>(v >> (8 * i) & 0xff);
}
void append32(std::string& b, std::uint32_t v) {
  b.append(4, '\0');
  put32(b, b.size() - 4, v);
}

bool same_name(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

std::uint32_t crc_of(std::string_view data) {
  uLong crc = crc32(0L, Z_NULL, 0);
  for (std::size_t at = 0; at < data.size();) {
    const auto n = static_cast<uInt>(std::min<std::size_t>(data.size() - at, 1u << 30));
    crc = crc32(crc, reinterpret_cast<const Bytef*>(data.data() + at), n);
    at += n;
  }
  return static_cast<std::uint32_t>(crc);
}

// Raw deflate (no zlib header), as ZIP stores it.
std::string deflate_raw(std::string_view data) {
  z_stream s{};
  if (deflateInit2(&s, Z_DEFAULT_COMPRESSION, Z_DEFLATED, -MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw MeshIoError("zlib cannot start compressing");
  std::string out(deflateBound(&s, static_cast<uLong>(data.size())), '\0');
  s.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  s.avail_in = static_cast<uInt>(data.size());
  s.next_out = reinterpret_cast<Bytef*>(out.data());
  s.avail_out = static_cast<uInt>(out.size());
  const int status = deflate(&s, Z_FINISH);
  out.resize(s.total_out);
  deflateEnd(&s);
  if (status != Z_STREAM_END) throw MeshIoError("zlib could not compress an entry");
  return out;
}

}  // namespace

ZipArchive::ZipArchive(std::string bytes, std::size_t max_entry_bytes, std::string source)
    : bytes_(std::move(bytes)), max_entry_bytes_(max_entry_bytes), source_(std::move(source)) {
  const std::size_t by_ratio = std::max(kMinInflateBudget, bytes_.size() * kMaxInflateRatio);
  inflate_budget_ = std::min(max_entry_bytes_, by_ratio);
  read_central_directory();
}

void ZipArchive::fail(const std::string& what) const { throw MeshIoError(source_ + ": " + what); }

void ZipArchive::read_central_directory() {
  // The end record sits in the last 64 KiB + 22 bytes (its comment is at most 65535 bytes).
  if (bytes_.size() < kEndFixed) fail("too short for a ZIP archive");
  std::size_t at = bytes_.size() - kEndFixed;
  const std::size_t lowest = bytes_.size() > kEndFixed + 0xffff ? bytes_.size() - kEndFixed - 0xffff : 0;
  while (get32(bytes_, at) != kEndRecord || at + kEndFixed + get16(bytes_, at + 20) != bytes_.size()) {
    if (at == lowest) fail("not a ZIP archive (no end of central directory record)");
    --at;
  }
  end_record_ = at;
  const std::uint16_t disk = get16(bytes_, at + 4), directory_disk = get16(bytes_, at + 6);
  const std::uint16_t count = get16(bytes_, at + 10);
  const std::uint32_t size = get32(bytes_, at + 12), offset = get32(bytes_, at + 16);
  if (disk != 0 || directory_disk != 0) fail("multi-disk ZIP archives are not read");
  if (count == 0xffff || size == 0xffffffff || offset == 0xffffffff) fail("ZIP64 archives are not read");
  if (std::size_t{offset} + size > end_record_) fail("the ZIP central directory runs past its end record");
  central_directory_ = offset;
  std::size_t record = offset;
  for (std::uint16_t i = 0; i < count; ++i) {
    if (record + kCentralFixed > end_record_ || get32(bytes_, record) != kCentralRecord)
      fail("ZIP central directory record " + std::to_string(i) + " is damaged");
    ZipEntry e;
    e.central_record = record;
    e.flags = get16(bytes_, record + 8);
    e.method = get16(bytes_, record + 10);
    e.crc = get32(bytes_, record + 16);
    e.compressed_size = get32(bytes_, record + 20);
    e.size = get32(bytes_, record + 24);
    const std::size_t name_length = get16(bytes_, record + 28), extra = get16(bytes_, record + 30),
                      comment = get16(bytes_, record + 32);
    e.local_header = get32(bytes_, record + 42);
    if (record + kCentralFixed + name_length + extra + comment > end_record_)
      fail("a ZIP entry name runs past the directory");
    e.name = bytes_.substr(record + kCentralFixed, name_length);
    if (e.flags & 1) fail("'" + e.name + "' is encrypted");
    if (e.compressed_size == 0xffffffff || e.size == 0xffffffff || e.local_header == 0xffffffff)
      fail("ZIP64 archives are not read");
    if (e.local_header + kLocalFixed > central_directory_ || get32(bytes_, e.local_header) != kLocalHeader)
      fail("the local header of '" + e.name + "' is missing");
    e.data = e.local_header + kLocalFixed + get16(bytes_, e.local_header + 26) + get16(bytes_, e.local_header + 28);
    if (e.data + e.compressed_size > central_directory_) fail("the data of '" + e.name + "' runs past the archive");
    entries_.push_back(std::move(e));
    record += kCentralFixed + name_length + extra + comment;
  }
}

const ZipEntry* ZipArchive::find(std::string_view name) const {
  for (const ZipEntry& e : entries_)
    if (same_name(e.name, name)) return &e;
  return nullptr;
}

std::string ZipArchive::extract(const ZipEntry& entry) const {
  if (entry.size > max_entry_bytes_)
    throw MeshLimitError(source_ + ": '" + entry.name + "' is " + std::to_string(entry.size) +
                         " bytes uncompressed, above the limit of " + std::to_string(max_entry_bytes_));
  // One budget for every extraction: entries each under the limit, or one entry extracted again
  // for every reference to it, must not add up past it.
  if (entry.size > inflate_budget_ - extracted_bytes_)
    throw MeshLimitError(source_ + ": extracting '" + entry.name +
                         "' would inflate the archive's entries to more than " + std::to_string(inflate_budget_) +
                         " bytes together");
  extracted_bytes_ += entry.size;
  const std::string_view data(bytes_.data() + entry.data, entry.compressed_size);
  std::string out;
  if (entry.method == 0) {
    if (entry.compressed_size != entry.size) fail("the stored entry '" + entry.name + "' has two sizes");
    out.assign(data);
  } else if (entry.method == 8) {
    // Inflate into exactly the declared size: a stream that wants more is refused, not followed.
    out.assign(entry.size, '\0');
    z_stream s{};
    if (inflateInit2(&s, -MAX_WBITS) != Z_OK) fail("zlib cannot start decompressing");
    s.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
    s.avail_in = static_cast<uInt>(data.size());
    s.next_out = reinterpret_cast<Bytef*>(out.data());
    s.avail_out = static_cast<uInt>(out.size());
    const int status = inflate(&s, Z_FINISH);
    const auto produced = s.total_out;
    inflateEnd(&s);
    if (status != Z_STREAM_END || produced != entry.size)
      fail("'" + entry.name + "' does not inflate to its declared " + std::to_string(entry.size) + " bytes");
  } else {
    fail("'" + entry.name + "' uses ZIP compression method " + std::to_string(entry.method) +
         "; only stored and deflate are read");
  }
  if (crc_of(out) != entry.crc) fail("'" + entry.name + "' fails its CRC-32 check");
  return out;
}

std::string ZipArchive::with_contents(const std::map<std::string, std::string>& contents) const {
  // Entries in file order; each spans from its local header to the next one (or the directory),
  // which takes its data descriptor and any bytes between along.
  std::vector<const ZipEntry*> order;
  for (const ZipEntry& e : entries_) order.push_back(&e);
  std::sort(order.begin(), order.end(),
            [](const ZipEntry* a, const ZipEntry* b) { return a->local_header < b->local_header; });
  std::string out = bytes_.substr(0, order.empty() ? central_directory_ : order.front()->local_header);
  struct Moved {
    std::size_t local_header;
    std::uint32_t crc, compressed_size, size;
  };
  std::map<const ZipEntry*, Moved> moved;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const ZipEntry& e = *order[i];
    const std::size_t end = i + 1 < order.size() ? order[i + 1]->local_header : central_directory_;
    auto replacement = contents.find(e.name);
    Moved m{out.size(), e.crc, e.compressed_size, e.size};
    if (replacement == contents.end()) {
      out.append(bytes_, e.local_header, end - e.local_header);
    } else {
      const std::string& plain = replacement->second;
      const std::string packed = e.method == 8 ? deflate_raw(plain) : plain;
      if (packed.size() >= 0xffffffffu || plain.size() >= 0xffffffffu) fail("'" + e.name + "' would need ZIP64");
      m = {out.size(), crc_of(plain), static_cast<std::uint32_t>(packed.size()),
           static_cast<std::uint32_t>(plain.size())};
      std::string header = bytes_.substr(e.local_header, e.data - e.local_header);
      if (!(e.flags & 8)) {
        put32(header, 14, m.crc);
        put32(header, 18, m.compressed_size);
        put32(header, 22, m.size);
      }
      out += header;
      out += packed;
      if (e.flags & 8) {  // sizes follow the data, in a descriptor with its signature
        append32(out, kDescriptor);
        append32(out, m.crc);
        append32(out, m.compressed_size);
        append32(out, m.size);
      }
    }
    moved[&e] = m;
  }
  const std::size_t directory = out.size();
  out.append(bytes_, central_directory_, end_record_ - central_directory_);
  for (const ZipEntry& e : entries_) {
    const Moved& m = moved.at(&e);
    const std::size_t at = directory + (e.central_record - central_directory_);
    put32(out, at + 16, m.crc);
    put32(out, at + 20, m.compressed_size);
    put32(out, at + 24, m.size);
    put32(out, at + 42, static_cast<std::uint32_t>(m.local_header));
  }
  const std::size_t end = out.size();
  out.append(bytes_, end_record_, std::string::npos);
  put32(out, end + 12, static_cast<std::uint32_t>(end - directory));
  put32(out, end + 16, static_cast<std::uint32_t>(directory));
  if (out.size() >= 0xffffffffu) fail("the archive would need ZIP64");
  return out;
}

namespace {

void append16(std::string& b, std::uint16_t v) {
  b.push_back(static_cast<char>(v & 0xff));
  b.push_back(static_cast<char>(v >> 8));
}

// The fields a local header and a central record share, from "version needed" to the name's length.
void append_entry_fields(std::string& b, std::uint32_t crc, std::uint32_t size, std::uint16_t name_length) {
  append16(b, 20);    // version needed: 2.0
  append16(b, 0);     // flags
  append16(b, 0);     // stored
  append16(b, 0);     // time
  append16(b, 0x21);  // date: 1980-01-01
  append32(b, crc);
  append32(b, size);  // compressed: stored
  append32(b, size);
  append16(b, name_length);
  append16(b, 0);  // extra field length
}

void check_entry_name(const std::string& name, const std::set<std::string>& seen) {
  if (name.empty() || name.front() == '/' || name.find("..") != std::string::npos ||
      name.find('\\') != std::string::npos)
    throw MeshIoError("a ZIP entry cannot be named '" + name + "'");
  if (seen.count(name)) throw MeshIoError("a ZIP entry named '" + name + "' twice");
}

}  // namespace

std::string write_zip(const std::vector<std::pair<std::string, std::string>>& files) {
  std::string out, directory;
  std::set<std::string> seen;
  for (const auto& [name, bytes] : files) {
    check_entry_name(name, seen);
    seen.insert(name);
    if (bytes.size() >= 0xffffffffu || out.size() >= 0xffffffffu) throw MeshIoError("the archive would need ZIP64");
    const std::uint32_t crc = crc_of(bytes), size = static_cast<std::uint32_t>(bytes.size());
    const auto name_length = static_cast<std::uint16_t>(name.size());
    append32(directory, kCentralRecord);
    append16(directory, 20);  // made by: 2.0
    append_entry_fields(directory, crc, size, name_length);
    append16(directory, 0);  // comment length
    append16(directory, 0);  // disk
    append16(directory, 0);  // internal attributes
    append32(directory, 0);  // external attributes
    append32(directory, static_cast<std::uint32_t>(out.size()));
    directory += name;
    append32(out, kLocalHeader);
    append_entry_fields(out, crc, size, name_length);
    out += name;
    out += bytes;
  }
  if (out.size() + directory.size() >= 0xffffffffu || files.size() >= 0xffff)
    throw MeshIoError("the archive would need ZIP64");
  const auto offset = static_cast<std::uint32_t>(out.size());
  out += directory;
  append32(out, kEndRecord);
  append16(out, 0);  // this disk
  append16(out, 0);  // the directory's disk
  append16(out, static_cast<std::uint16_t>(files.size()));
  append16(out, static_cast<std::uint16_t>(files.size()));
  append32(out, static_cast<std::uint32_t>(directory.size()));
  append32(out, offset);
  append16(out, 0);  // comment length
  return out;
}

}  // namespace meshmark
