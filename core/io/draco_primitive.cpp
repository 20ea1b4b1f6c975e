#include "core/io/draco_primitive.hpp"

#include <draco/attributes/attribute_octahedron_transform.h>
#include <draco/attributes/attribute_quantization_transform.h>
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/compression/expert_encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

#include "core/io/mesh_io_error.hpp"

namespace meshmark {

namespace {

// Reads the header fields in order; any read past the end gives up (none).
class HeaderReader {
 public:
  explicit HeaderReader(std::string_view bytes) : bytes_(bytes) {}
  bool ok() const { return ok_; }
  std::uint64_t byte() { return take(1); }
  std::uint64_t u16() { return take(2); }
  std::uint64_t u32() { return take(4); }
  std::uint64_t varint() {  // LEB128, at most 5 bytes for a 32-bit count
    std::uint64_t value = 0;
    for (int shift = 0; shift < 35; shift += 7) {
      const std::uint64_t b = byte();
      value |= (b & 0x7f) << shift;
      if (!(b & 0x80)) return value;
    }
    ok_ = false;
    return 0;
  }
  // A count as the bitstream version stores it: a fixed 32-bit word before 2.0, a varint since.
  std::uint64_t count(int version) { return version < 0x0200 ? u32() : varint(); }
  void skip(std::uint64_t n) {
    if (!ok_ || bytes_.size() - at_ < n) ok_ = false;
    else at_ += n;
  }

 private:
  std::uint64_t take(std::size_t n) {  // little-endian
    if (!ok_ || bytes_.size() - at_ < n) return ok_ = false, 0;
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < n; ++i) value |= std::uint64_t(static_cast<unsigned char>(bytes_[at_ + i])) << (8 * i);
    at_ += n;
    return value;
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
  bool ok_ = true;
};

// One metadata element and its sub-elements, without keeping them. libdraco sizes an entry's value
// by its declared length before reading it and nests without a bound, so both are checked here.
bool skip_metadata_element(HeaderReader& in, int depth) {
  constexpr int kMaxDepth = 32;
  if (depth > kMaxDepth) return false;
  for (std::uint64_t entries = in.varint(); in.ok() && entries > 0; --entries) {
    in.skip(in.byte());  // name
    const std::uint64_t value_size = in.varint();
    if (value_size == 0) return false;
    in.skip(value_size);
  }
  for (std::uint64_t children = in.varint(); in.ok() && children > 0; --children) {
    in.skip(in.byte());  // name
    if (!skip_metadata_element(in, depth + 1)) return false;
  }
  return in.ok();
}

// The geometry's metadata: one element per attribute (after its unique id), then the mesh's own.
bool skip_metadata(HeaderReader& in) {
  for (std::uint64_t attributes = in.varint(); in.ok() && attributes > 0; --attributes) {
    in.varint();  // attribute unique id
    if (!skip_metadata_element(in, 0)) return false;
  }
  return skip_metadata_element(in, 0);
}

std::optional<DracoDeclared> edgebreaker_declared(HeaderReader& in, int version) {
  in.byte();                                // traversal decoder
  if (version < 0x0202) in.count(version);  // new vertices (older streams)
  const std::uint64_t vertices = in.count(version);
  const std::uint64_t faces = in.count(version);
  if (!in.ok()) return std::nullopt;
  return DracoDeclared{vertices, faces};
}

std::unique_ptr<draco::Mesh> decode(std::string_view bytes, bool skip_transforms) {
  draco::DecoderBuffer buffer;
  buffer.Init(bytes.data(), bytes.size());
  draco::Decoder decoder;
  if (skip_transforms)
    for (const auto type :
         {draco::GeometryAttribute::POSITION, draco::GeometryAttribute::NORMAL, draco::GeometryAttribute::COLOR,
          draco::GeometryAttribute::TEX_COORD, draco::GeometryAttribute::GENERIC})
      decoder.SetSkipAttributeTransform(type);
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok())
    throw MeshIoError(std::string("the Draco stream cannot be decoded: ") + decoded.status().error_msg());
  return std::move(decoded).value();
}

}  // namespace

std::optional<DracoDeclared> draco_declared(std::string_view bytes) {
  if (bytes.substr(0, 5) != "DRACO") return std::nullopt;
  HeaderReader in(bytes.substr(5));
  const int version = static_cast<int>(in.byte() << 8 | in.byte());
  const std::uint64_t geometry = in.byte(), method = in.byte();
  const std::uint64_t flags = in.u16();
  constexpr std::uint64_t kTriangularMesh = 1, kSequential = 0, kEdgebreaker = 1, kMetadata = 0x8000;
  if (!in.ok() || geometry != kTriangularMesh) return std::nullopt;
  if ((flags & kMetadata) && !skip_metadata(in)) return std::nullopt;
  if (method == kEdgebreaker) return edgebreaker_declared(in, version);
  if (method != kSequential) return std::nullopt;
  const std::uint64_t faces = version < 0x0202 ? in.u32() : in.varint();
  const std::uint64_t points = version < 0x0202 ? in.u32() : in.varint();
  if (!in.ok()) return std::nullopt;
  return DracoDeclared{points, faces};
}

DracoPrimitive::DracoPrimitive(std::string_view bytes, int position_id, const DracoLimits& limits) {
  const auto declared = draco_declared(bytes);
  if (!declared)
    throw MeshIoError(
        "the Draco stream's header cannot be read (not a triangle mesh in bitstream 1.x-2.2, or cut short), "
        "so its size cannot be checked before decoding");
  if (declared->vertices > limits.vertices || declared->faces > limits.faces)
    throw MeshLimitError("the Draco stream declares " + std::to_string(declared->vertices) + " vertices and " +
                         std::to_string(declared->faces) + " faces, over the limit of " +
                         std::to_string(limits.vertices) + " and " + std::to_string(limits.faces) +
                         " (refused before decoding)");
  mesh_ = decode(bytes, false);
  const draco::PointAttribute* position = mesh_->GetAttributeByUniqueId(static_cast<std::uint32_t>(position_id));
  if (!position || position->num_components() != 3 || position->data_type() != draco::DT_FLOAT32)
    throw MeshIoError("the Draco stream has no attribute " + std::to_string(position_id) +
                      " of three 32-bit floats for POSITION");
  for (int i = 0; i < mesh_->num_attributes(); ++i)
    if (mesh_->attribute(i) == position) position_attribute_ = i;
  // The quantization each attribute was stored with, to store it alike again.
  const auto raw = decode(bytes, true);
  bits_.assign(static_cast<std::size_t>(mesh_->num_attributes()), 0);
  for (int i = 0; i < raw->num_attributes() && i < mesh_->num_attributes(); ++i) {
    const draco::PointAttribute& a = *raw->attribute(i);
    const auto* transform = a.GetAttributeTransformData();
    if (!transform) continue;
    if (transform->transform_type() == draco::ATTRIBUTE_QUANTIZATION_TRANSFORM) {
      draco::AttributeQuantizationTransform q;
      if (q.InitFromAttribute(a)) bits_[static_cast<std::size_t>(i)] = q.quantization_bits();
    } else if (transform->transform_type() == draco::ATTRIBUTE_OCTAHEDRON_TRANSFORM) {
      draco::AttributeOctahedronTransform q;
      if (q.InitFromAttribute(a)) bits_[static_cast<std::size_t>(i)] = q.quantization_bits();
    }
  }
  positions_.resize(mesh_->num_points(), 3);
  for (draco::PointIndex p(0); p < mesh_->num_points(); ++p) {
    float v[3];
    position->GetMappedValue(p, v);
    positions_.row(p.value()) << v[0], v[1], v[2];
  }
  faces_.resize(mesh_->num_faces(), 3);
  for (draco::FaceIndex f(0); f < mesh_->num_faces(); ++f)
    for (int k = 0; k < 3; ++k) faces_(f.value(), k) = static_cast<int>(mesh_->face(f)[k].value());
  // libdraco's sequential decoder does not check its indices against the points it decoded.
  if (faces_.size() > 0 && (faces_.minCoeff() < 0 || faces_.maxCoeff() >= positions_.rows()))
    throw MeshIoError("the Draco stream has a face whose corner is not one of its " +
                      std::to_string(positions_.rows()) + " points");
}

DracoPrimitive::~DracoPrimitive() = default;
DracoPrimitive::DracoPrimitive(DracoPrimitive&&) noexcept = default;

int DracoPrimitive::position_bits() const { return bits_[static_cast<std::size_t>(position_attribute_)]; }

std::string DracoPrimitive::encode(const Vertices& positions) const {
  draco::Mesh copy;
  copy.Copy(*mesh_);
  draco::PointAttribute* position = copy.attribute(position_attribute_);
  for (draco::PointIndex p(0); p < copy.num_points(); ++p) {
    const float v[3] = {static_cast<float>(positions(p.value(), 0)), static_cast<float>(positions(p.value(), 1)),
                        static_cast<float>(positions(p.value(), 2))};
    position->SetAttributeValue(position->mapped_index(p), v);
  }
  draco::ExpertEncoder encoder(copy);
  for (std::size_t i = 0; i < bits_.size(); ++i)
    if (bits_[i] > 0) encoder.SetAttributeQuantization(static_cast<int>(i), bits_[i]);
  draco::EncoderBuffer out;
  const draco::Status status = encoder.EncodeToBuffer(&out);
  if (!status.ok()) throw MeshIoError(std::string("the Draco stream cannot be encoded again: ") + status.error_msg());
  return std::string(out.data(), out.size());
}

std::string draco_encode_positions(const Mesh& mesh, int bits) {
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(static_cast<int>(mesh.F.rows()));
  const int position = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    float corner[3][3];
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) corner[c][k] = static_cast<float>(mesh.V(mesh.F(f, c), k));
    builder.SetAttributeValuesForFace(position, draco::FaceIndex(static_cast<std::uint32_t>(f)), corner[0], corner[1],
                                      corner[2]);
  }
  std::unique_ptr<draco::Mesh> m = builder.Finalize();
  if (!m) throw MeshIoError("Draco could not build the mesh");
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, bits);
  draco::EncoderBuffer out;
  const draco::Status status = encoder.EncodeMeshToBuffer(*m, &out);
  if (!status.ok()) throw MeshIoError(std::string("Draco encoding failed: ") + status.error_msg());
  return std::string(out.data(), out.size());
}

Mesh draco_decode_positions(std::string_view bytes) {
  const auto m = decode(bytes, false);
  const draco::PointAttribute* position = m->GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (!position) throw MeshIoError("the Draco stream has no positions");
  Mesh out;
  out.V.resize(m->num_points(), 3);
  for (draco::PointIndex p(0); p < m->num_points(); ++p) {
    float v[3];
    position->GetMappedValue(p, v);
    out.V.row(p.value()) << v[0], v[1], v[2];
  }
  out.F.resize(m->num_faces(), 3);
  for (draco::FaceIndex f(0); f < m->num_faces(); ++f)
    for (int k = 0; k < 3; ++k) out.F(f.value(), k) = static_cast<int>(m->face(f)[k].value());
  return out;
}

}  // namespace meshmark
