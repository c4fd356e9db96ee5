#include "asset/gltf_compression.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <meshoptimizer.h>

#include "asset/draco_mesh.h"
#include "asset/gltf_accessor.h"
#include "asset/gltf_limits.h"

// Why the loader decodes Draco itself rather than through tinygltf's
// TINYGLTF_ENABLE_DRACO: Debian ships tinygltf as a prebuilt libtinygltf.so
// (TINYGLTF_IMPLEMENTATION is compiled there, without Draco: the library links no
// libdraco and exports no Draco code), so the switch would mean compiling our own
// copy of tinygltf. And its ParseDracoExtension is not fit for untrusted files:
// ParsePrimitive drops its return value (a failed decode loads silently with
// accessors that have no data), and it indexes bufferViews, buffers and Draco
// attribute ids unchecked (a bad id dereferences null). Decoding here, after
// tinygltf, with draco::Decoder (in engine_draco, see draco_mesh.h for why it is
// a library of its own) gives every failure a message and the decoded data the
// same bounds checks as the rest of the file.

namespace engine::gltf {
namespace {

constexpr const char* kMeshopt = "EXT_meshopt_compression";
constexpr const char* kDraco = "KHR_draco_mesh_compression";

std::string str(std::uint64_t v) { return std::to_string(v); }

// A non-negative integer member of an extension object; `fallback` when absent
// (nullopt: the member is required).
Result<std::uint64_t> unsignedField(const tinygltf::Value& object, const char* key,
                                    std::optional<std::uint64_t> fallback, const std::string& where) {
  if (!object.Has(key)) {
    if (fallback) return *fallback;
    return makeError(where + ": " + key + " is missing");
  }
  const tinygltf::Value& v = object.Get(key);
  const double d = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
  if (!(d >= 0.0) || d > 9007199254740992.0 || std::floor(d) != d)
    return makeError(where + ": " + key + " must be an integer >= 0");
  return static_cast<std::uint64_t>(d);
}

// Appends `bytes` as a new buffer; returns its index.
int addBuffer(tinygltf::Model& model, std::vector<unsigned char> bytes) {
  tinygltf::Buffer buffer;
  buffer.data = std::move(bytes);
  model.buffers.push_back(std::move(buffer));
  return static_cast<int>(model.buffers.size() - 1);
}

// Appends `bytes` as a new buffer with one bufferView over all of it.
int addView(tinygltf::Model& model, std::vector<unsigned char> bytes) {
  tinygltf::BufferView view;
  view.byteOffset = 0;
  view.byteLength = bytes.size();
  view.buffer = addBuffer(model, std::move(bytes));
  model.bufferViews.push_back(std::move(view));
  return static_cast<int>(model.bufferViews.size() - 1);
}

bool isFallbackBuffer(const tinygltf::ExtensionMap& extensions) {
  auto ext = extensions.find(kMeshopt);
  if (ext == extensions.end() || !ext->second.Has("fallback")) return false;
  const tinygltf::Value& fallback = ext->second.Get("fallback");
  return fallback.IsBool() && fallback.Get<bool>();
}

// ---- EXT_meshopt_compression --------------------------------------------------

struct MeshoptView {
  std::uint64_t buffer = 0, byteOffset = 0, byteLength = 0, byteStride = 0, count = 0;
  std::string mode, filter;
};

Result<MeshoptView> readMeshoptExtension(const tinygltf::Value& ext, const std::string& where) {
  if (!ext.IsObject()) return makeError(where + ": must be an object");
  MeshoptView v;
  const std::optional<std::uint64_t> required;
  Status status = Ok{};
  auto field = [&](const char* key, std::optional<std::uint64_t> fallback) -> std::uint64_t {
    auto value = unsignedField(ext, key, fallback, where);
    if (!value && status) status = value.error();
    return value ? *value : 0;
  };
  v.buffer = field("buffer", required);
  v.byteOffset = field("byteOffset", 0);
  v.byteLength = field("byteLength", required);
  v.byteStride = field("byteStride", required);
  v.count = field("count", required);
  if (!status) return status.error();
  auto text = [&](const char* key, const char* fallback) -> std::optional<std::string> {
    if (!ext.Has(key)) return fallback ? std::optional<std::string>(fallback) : std::nullopt;
    return ext.Get(key).IsString() ? std::optional<std::string>(ext.Get(key).Get<std::string>()) : std::nullopt;
  };
  auto mode = text("mode", nullptr);
  auto filter = text("filter", "NONE");
  if (!mode) return makeError(where + ": mode must be ATTRIBUTES, TRIANGLES or INDICES");
  if (!filter) return makeError(where + ": filter must be a string");
  v.mode = *mode;
  v.filter = *filter;
  return v;
}

// meshoptimizer asserts on sizes it cannot decode (and Debian's build may keep
// asserts), so every combination is checked here first.
Status checkMeshoptShape(const MeshoptView& v, const std::string& where) {
  if (v.count == 0 || v.count > kMaxAccessorElements)
    return makeError(where + ": count " + str(v.count) + " is outside [1, " + str(kMaxAccessorElements) + "]");
  if (v.mode == "ATTRIBUTES") {
    if (v.byteStride == 0 || v.byteStride > 256 || v.byteStride % 4 != 0)
      return makeError(where + ": ATTRIBUTES need a byteStride that is a multiple of 4 in [4, 256], not " +
                       str(v.byteStride));
  } else if (v.mode == "TRIANGLES" || v.mode == "INDICES") {
    if (v.byteStride != 2 && v.byteStride != 4)
      return makeError(where + ": " + v.mode + " need a byteStride of 2 or 4, not " + str(v.byteStride));
    if (v.mode == "TRIANGLES" && v.count % 3 != 0)
      return makeError(where + ": TRIANGLES count " + str(v.count) + " is not a multiple of 3");
  } else {
    return makeError(where + ": unknown mode \"" + v.mode + "\"");
  }
  const bool filtered = v.filter != "NONE";
  if (filtered && v.mode != "ATTRIBUTES") return makeError(where + ": filter " + v.filter + " needs mode ATTRIBUTES");
  if (v.filter == "OCTAHEDRAL" && v.byteStride != 4 && v.byteStride != 8)
    return makeError(where + ": OCTAHEDRAL needs a byteStride of 4 or 8, not " + str(v.byteStride));
  if (v.filter == "QUATERNION" && v.byteStride != 8)
    return makeError(where + ": QUATERNION needs a byteStride of 8, not " + str(v.byteStride));
  if (filtered && v.filter != "OCTAHEDRAL" && v.filter != "QUATERNION" && v.filter != "EXPONENTIAL")
    return makeError(where + ": unknown filter \"" + v.filter + "\"");
  return Ok{};
}

// The decoders return 0 on success and a negative code for data that is cut short
// or not meshopt's; the filters cannot fail once the shape is checked.
int runMeshopt(const MeshoptView& v, const unsigned char* src, std::vector<unsigned char>& out) {
  const std::size_t count = static_cast<std::size_t>(v.count), stride = static_cast<std::size_t>(v.byteStride);
  const std::size_t srcBytes = static_cast<std::size_t>(v.byteLength);
  if (v.mode == "TRIANGLES") return meshopt_decodeIndexBuffer(out.data(), count, stride, src, srcBytes);
  if (v.mode == "INDICES") return meshopt_decodeIndexSequence(out.data(), count, stride, src, srcBytes);
  const int rc = meshopt_decodeVertexBuffer(out.data(), count, stride, src, srcBytes);
  if (rc != 0) return rc;
  if (v.filter == "OCTAHEDRAL") meshopt_decodeFilterOct(out.data(), count, stride);
  if (v.filter == "QUATERNION") meshopt_decodeFilterQuat(out.data(), count, stride);
  if (v.filter == "EXPONENTIAL") meshopt_decodeFilterExp(out.data(), count, stride);
  return 0;
}

// Decodes bufferView `index` into a buffer of its own and points the view at it.
// `budget` is what decoded data may still take: meshopt shrinks constant data to
// almost nothing, so a small file could otherwise ask for gigabytes.
Status decodeMeshoptView(tinygltf::Model& model, std::size_t index, std::uint64_t& budget, const std::string& file) {
  const std::string where = file + ": bufferView " + str(index) + ": " + kMeshopt;
  auto parsed = readMeshoptExtension(model.bufferViews[index].extensions.at(kMeshopt), where);
  if (!parsed) return parsed.error();
  const MeshoptView v = *parsed;
  if (Status s = checkMeshoptShape(v, where); !s) return s;
  if (v.buffer >= model.buffers.size()) return makeError(where + ": buffer " + str(v.buffer) + " does not exist");
  const std::vector<unsigned char>& source = model.buffers[static_cast<std::size_t>(v.buffer)].data;
  if (v.byteOffset > source.size() || v.byteLength > source.size() - v.byteOffset)
    return makeError(where + ": bytes [" + str(v.byteOffset) + ", " + str(v.byteOffset + v.byteLength) +
                     ") run past buffer " + str(v.buffer) + " of " + str(source.size()) + " bytes");
  const std::uint64_t decodedBytes = v.count * v.byteStride;
  if (decodedBytes > budget)
    return makeError(where + ": decodes to " + str(decodedBytes) + " bytes, more than the " +
                     str(kMaxModelFileBytes) + " all views together may take");
  budget -= decodedBytes;
  tinygltf::BufferView& view = model.bufferViews[index];
  // Accessors are checked against the view's own byteLength: it may not promise
  // more than the decoded data holds.
  if (view.byteLength > decodedBytes)
    return makeError(where + ": the bufferView's byteLength " + str(view.byteLength) + " is more than count * byteStride = " +
                     str(decodedBytes));
  std::vector<unsigned char> out(static_cast<std::size_t>(decodedBytes), 0);
  const int rc = runMeshopt(v, source.data() + v.byteOffset, out);
  if (rc != 0)
    return makeError(where + ": decode failed: meshopt error " + std::to_string(rc) + " (" + v.mode + " of " +
                     str(v.count) + " x " + str(v.byteStride) + " bytes from " + str(v.byteLength) +
                     "; the data is truncated or corrupt)");
  view.buffer = addBuffer(model, std::move(out));
  view.byteOffset = 0;
  return Ok{};
}

Status decodeMeshopt(tinygltf::Model& model, const std::string& file) {
  // Fallback buffers exist only to be named by compressed views: the placeholder
  // byte of kFallbackBufferUri goes, so a plain view into one fails its bounds check.
  for (tinygltf::Buffer& buffer : model.buffers)
    if (isFallbackBuffer(buffer.extensions) && buffer.uri == kFallbackBufferUri) buffer.data.clear();
  std::uint64_t budget = kMaxModelFileBytes;
  const std::size_t views = model.bufferViews.size();  // addView appends; those need no decoding
  for (std::size_t i = 0; i < views; ++i) {
    if (!model.bufferViews[i].extensions.count(kMeshopt)) continue;
    if (Status s = decodeMeshoptView(model, i, budget, file); !s) return s;
  }
  return Ok{};
}

// ---- KHR_draco_mesh_compression -----------------------------------------------


Result<DracoMesh> decodeDracoBytes(const tinygltf::Model& model, const tinygltf::Value& ext, const std::string& where) {
  auto viewIndex = unsignedField(ext, "bufferView", std::nullopt, where);
  if (!viewIndex) return viewIndex.error();
  if (*viewIndex >= model.bufferViews.size())
    return makeError(where + ": bufferView " + str(*viewIndex) + " does not exist");
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(*viewIndex)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
    return makeError(where + ": bufferView " + str(*viewIndex) + ": buffer " + std::to_string(view.buffer) +
                     " does not exist");
  const std::vector<unsigned char>& data = model.buffers[static_cast<std::size_t>(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
    return makeError(where + ": bufferView " + str(*viewIndex) + ": bytes [" + str(view.byteOffset) + ", " +
                     str(view.byteOffset + view.byteLength) + ") run past buffer " + std::to_string(view.buffer) +
                     " of " + str(data.size()) + " bytes");
  auto mesh = DracoMesh::decode(std::span(data.data() + view.byteOffset, view.byteLength));
  if (!mesh) return makeError(where + ": decode failed: " + mesh.error().message);
  if (mesh->points() == 0 || mesh->points() > kMaxAccessorElements ||
      std::uint64_t{mesh->triangles()} * 3 > kMaxAccessorElements)
    return makeError(where + ": decoded " + str(mesh->points()) + " points and " + str(mesh->triangles()) +
                     " triangles, outside [1, " + str(kMaxAccessorElements) + "] elements");
  return mesh;
}

Status checkAccessor(const tinygltf::Model& model, int accessor, const std::string& where) {
  if (accessor < 0 || static_cast<std::size_t>(accessor) >= model.accessors.size())
    return makeError(where + ": accessor " + std::to_string(accessor) + " does not exist");
  return Ok{};
}

// The triangles as the primitive's index accessor, in its component type.
Status writeDracoIndices(tinygltf::Model& model, const DracoMesh& mesh, int accessorIndex, const std::string& where) {
  if (Status s = checkAccessor(model, accessorIndex, where + ": indices"); !s) return s;
  tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(accessorIndex)];
  const int bytes = componentBytes(accessor.componentType);
  const bool integer = accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                       accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                       accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  if (!integer) return makeError(where + ": indices: accessor " + std::to_string(accessorIndex) + " is not unsigned");
  const std::uint64_t largest = bytes == 4 ? 0xFFFFFFFFull : (1ull << (8 * bytes)) - 1;
  if (mesh.points() - 1 > largest)
    return makeError(where + ": indices: " + str(mesh.points()) + " points do not fit accessor " +
                     std::to_string(accessorIndex) + "'s " + std::to_string(bytes) + "-byte indices");
  const std::vector<std::uint32_t> indices = mesh.indices();
  std::vector<unsigned char> out(indices.size() * static_cast<std::size_t>(bytes));
  for (std::size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] >= mesh.points()) return makeError(where + ": decode failed: triangle index past the points");
    std::memcpy(out.data() + i * static_cast<std::size_t>(bytes), &indices[i], static_cast<std::size_t>(bytes));  // little-endian: the low bytes
  }
  accessor.bufferView = addView(model, std::move(out));
  accessor.byteOffset = 0;
  accessor.count = indices.size();
  return Ok{};
}

// One `attributes` entry of the extension: Draco attribute `id` into the accessor
// the primitive names for `semantic`, in that accessor's type.
Status writeDracoAttribute(tinygltf::Model& model, const tinygltf::Primitive& prim, const DracoMesh& mesh,
                           const std::string& semantic, const tinygltf::Value& id, const std::string& where) {
  const std::string name = where + ": " + semantic;
  auto it = prim.attributes.find(semantic);
  if (it == prim.attributes.end()) return makeError(name + ": the primitive has no such attribute");
  if (Status s = checkAccessor(model, it->second, name); !s) return s;
  if (!id.IsInt() || id.GetNumberAsInt() < 0) return makeError(name + ": the Draco attribute id must be an integer >= 0");
  tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(it->second)];
  const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type));
  if (components < 1 || components > 4 || componentBytes(accessor.componentType) == 0)
    return makeError(name + ": accessor " + std::to_string(it->second) + " has an invalid type or componentType");
  auto values = mesh.attribute(static_cast<std::uint32_t>(id.GetNumberAsInt()), accessor.componentType, components);
  if (!values) return makeError(name + ": " + values.error().message);
  accessor.bufferView = addView(model, std::move(values).value());
  accessor.byteOffset = 0;
  accessor.count = mesh.points();
  return Ok{};
}

Status decodeDracoPrimitive(tinygltf::Model& model, tinygltf::Primitive& prim, const std::string& where) {
  const tinygltf::Value& ext = prim.extensions.at(kDraco);
  if (!ext.IsObject() || !ext.Has("attributes") || !ext.Get("attributes").IsObject())
    return makeError(where + ": attributes must be an object");
  auto mesh = decodeDracoBytes(model, ext, where);
  if (!mesh) return mesh.error();
  // Draco reorders the points, so a triangle mesh without an index accessor could
  // not be drawn in the order the file meant.
  if (prim.indices < 0) return makeError(where + ": the primitive has no indices, which a Draco mesh needs");
  if (Status s = writeDracoIndices(model, *mesh, prim.indices, where); !s) return s;
  const tinygltf::Value& attributes = ext.Get("attributes");
  for (const std::string& semantic : attributes.Keys())
    if (Status s = writeDracoAttribute(model, prim, *mesh, semantic, attributes.Get(semantic), where); !s) return s;
  return Ok{};
}

Status decodeDraco(tinygltf::Model& model, const std::string& file) {
  for (std::size_t m = 0; m < model.meshes.size(); ++m)
    for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      tinygltf::Primitive& prim = model.meshes[m].primitives[p];
      if (!prim.extensions.count(kDraco)) continue;
      const std::string where = file + ": mesh " + str(m) + " primitive " + str(p) + ": " + kDraco;
      if (Status s = decodeDracoPrimitive(model, prim, where); !s) return s;
    }
  return Ok{};
}

}  // namespace

namespace {

bool stubMeshoptFallbackBuffers(nlohmann::json& doc) {
  auto buffers = doc.find("buffers");
  if (buffers == doc.end() || !buffers->is_array()) return false;
  bool changed = false;
  for (auto& buffer : *buffers) {
    if (!buffer.is_object() || buffer.contains("uri")) continue;
    const auto ext = buffer.find("extensions");
    if (ext == buffer.end() || !ext->is_object() || !ext->contains(kMeshopt)) continue;
    const auto& meshopt = (*ext)[kMeshopt];
    const auto fallback = meshopt.is_object() ? meshopt.find("fallback") : meshopt.end();
    if (fallback == meshopt.end() || !fallback->is_boolean() || !fallback->get<bool>()) continue;
    buffer["uri"] = kFallbackBufferUri;
    buffer["byteLength"] = 1;
    changed = true;
  }
  return changed;
}

// The member `key` of `object` when it is an unsigned integer below `size`.
std::optional<std::size_t> indexMember(const nlohmann::json& object, const char* key, std::size_t size) {
  const auto it = object.find(key);
  if (it == object.end() || !it->is_number_unsigned() || it->get<std::uint64_t>() >= size) return std::nullopt;
  return it->get<std::size_t>();
}

bool stubDracoIndexViews(nlohmann::json& doc) {
  auto meshes = doc.find("meshes");
  auto accessors = doc.find("accessors");
  if (meshes == doc.end() || !meshes->is_array() || accessors == doc.end() || !accessors->is_array()) return false;
  bool changed = false;
  for (auto& mesh : *meshes) {
    const auto prims = mesh.is_object() ? mesh.find("primitives") : mesh.end();
    if (prims == mesh.end() || !prims->is_array()) continue;
    for (auto& prim : *prims) {
      const auto ext = prim.is_object() ? prim.find("extensions") : prim.end();
      if (ext == prim.end() || !ext->is_object() || !ext->contains(kDraco) || !(*ext)[kDraco].is_object()) continue;
      const auto view = (*ext)[kDraco].find("bufferView");
      const auto indices = indexMember(prim, "indices", accessors->size());
      if (view == (*ext)[kDraco].end() || !indices || !(*accessors)[*indices].is_object()) continue;
      auto& accessor = (*accessors)[*indices];
      if (accessor.contains("bufferView")) continue;
      accessor["bufferView"] = *view;
      changed = true;
    }
  }
  return changed;
}

}  // namespace

bool prepareCompressedJson(nlohmann::json& doc) {
  if (!doc.is_object()) return false;
  const bool fallbacks = stubMeshoptFallbackBuffers(doc);
  return stubDracoIndexViews(doc) || fallbacks;
}

// Meshopt first: a Draco bufferView could itself be meshopt-compressed (nothing
// forbids it), never the other way round.
Status decodeCompressedGeometry(tinygltf::Model& model, const std::string& file) {
  if (Status s = decodeMeshopt(model, file); !s) return s;
  return decodeDraco(model, file);
}

}  // namespace engine::gltf
