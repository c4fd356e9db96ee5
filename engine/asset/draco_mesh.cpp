#include "asset/draco_mesh.h"

#include <cstring>
#include <string>
#include <utility>

#include <draco/attributes/attribute_quantization_transform.h>
#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>

namespace engine::gltf {
namespace {

// Every point's value of `att` as `components` values of T, in point order (the
// order the indices refer to).
template <typename T>
bool convertPoints(const draco::Mesh& mesh, const draco::PointAttribute& att, int components,
                   std::vector<unsigned char>& out) {
  const std::size_t elementBytes = sizeof(T) * static_cast<std::size_t>(components);
  out.assign(mesh.num_points() * elementBytes, 0);
  std::vector<T> value(static_cast<std::size_t>(components));
  for (draco::PointIndex p(0); p < mesh.num_points(); ++p) {
    const draco::AttributeValueIndex at = att.mapped_index(p);
    if (at.value() >= att.size()) return false;
    if (!att.ConvertValue<T>(at, static_cast<std::int8_t>(components), value.data())) return false;
    std::memcpy(out.data() + p.value() * elementBytes, value.data(), elementBytes);
  }
  return true;
}

// glTF component types: 5120 BYTE, 5121 UNSIGNED_BYTE, 5122 SHORT,
// 5123 UNSIGNED_SHORT, 5125 UNSIGNED_INT, 5126 FLOAT.
bool convertAttribute(const draco::Mesh& mesh, const draco::PointAttribute& att, int componentType, int components,
                      std::vector<unsigned char>& out) {
  switch (componentType) {
    case 5120: return convertPoints<std::int8_t>(mesh, att, components, out);
    case 5121: return convertPoints<std::uint8_t>(mesh, att, components, out);
    case 5122: return convertPoints<std::int16_t>(mesh, att, components, out);
    case 5123: return convertPoints<std::uint16_t>(mesh, att, components, out);
    case 5125: return convertPoints<std::uint32_t>(mesh, att, components, out);
    case 5126: return convertPoints<float>(mesh, att, components, out);
    default: return false;
  }
}

draco::StatusOr<std::unique_ptr<draco::Mesh>> decodeBytes(std::span<const unsigned char> bytes, draco::Decoder& decoder) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  return decoder.DecodeMeshFromBuffer(&buffer);
}

}  // namespace

struct DracoMesh::Impl {
  std::unique_ptr<draco::Mesh> mesh;
};

DracoMesh::DracoMesh(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
DracoMesh::DracoMesh(DracoMesh&&) noexcept = default;
DracoMesh& DracoMesh::operator=(DracoMesh&&) noexcept = default;
DracoMesh::~DracoMesh() = default;

Result<DracoMesh> DracoMesh::decode(std::span<const unsigned char> bytes) {
  draco::Decoder decoder;
  auto decoded = decodeBytes(bytes, decoder);
  if (!decoded.ok()) return makeError(decoded.status().error_msg_string());
  auto impl = std::make_unique<Impl>();
  impl->mesh = std::move(decoded).value();
  return DracoMesh(std::move(impl));
}

std::uint32_t DracoMesh::points() const { return impl_->mesh->num_points(); }
std::uint32_t DracoMesh::triangles() const { return impl_->mesh->num_faces(); }

std::vector<std::uint32_t> DracoMesh::indices() const {
  const draco::Mesh& mesh = *impl_->mesh;
  std::vector<std::uint32_t> out;
  out.reserve(std::size_t{mesh.num_faces()} * 3);
  for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
    for (int corner = 0; corner < 3; ++corner) out.push_back(mesh.face(f)[corner].value());
  return out;
}

Result<std::vector<unsigned char>> DracoMesh::attribute(std::uint32_t id, int componentType, int components) const {
  const draco::Mesh& mesh = *impl_->mesh;
  const draco::PointAttribute* att = mesh.GetAttributeByUniqueId(id);
  const std::string name = "Draco attribute " + std::to_string(id);
  if (att == nullptr) return makeError(name + " is not in the data");
  if (att->num_components() != components)
    return makeError(name + " has " + std::to_string(att->num_components()) + " components, the accessor " +
                     std::to_string(components));
  std::vector<unsigned char> out;
  if (!convertAttribute(mesh, *att, componentType, components, out))
    return makeError("decode failed: " + name + "'s values do not convert to the accessor's component type");
  return out;
}

Result<double> DracoMesh::quantizationStep(std::span<const unsigned char> bytes, std::uint32_t id) {
  draco::Decoder decoder;
  // Without the dequantization the attribute keeps its transform's parameters.
  decoder.SetSkipAttributeTransform(draco::GeometryAttribute::POSITION);
  decoder.SetSkipAttributeTransform(draco::GeometryAttribute::TEX_COORD);
  auto decoded = decodeBytes(bytes, decoder);
  if (!decoded.ok()) return makeError(decoded.status().error_msg_string());
  const draco::PointAttribute* att = decoded.value()->GetAttributeByUniqueId(id);
  if (att == nullptr) return makeError("Draco attribute " + std::to_string(id) + " is not in the data");
  draco::AttributeQuantizationTransform q;
  if (!q.InitFromAttribute(*att) || q.quantization_bits() < 1 || q.quantization_bits() > 30) return 0.0;
  return static_cast<double>(q.range()) / static_cast<double>((1u << q.quantization_bits()) - 1);
}

}  // namespace engine::gltf
