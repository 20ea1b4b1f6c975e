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

DracoPrimitive::DracoPrimitive(std::string_view bytes, int position_id) {
  mesh_ = decode(bytes, false);
  const draco::PointAttribute* position = mesh_->GetAttributeByUniqueId(static_cast<std::uint32_t>(position_id));
  if (!position || position->num_components() != 3)
    throw MeshIoError("the Draco stream has no 3-component attribute " + std::to_string(position_id) + " for POSITION");
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
