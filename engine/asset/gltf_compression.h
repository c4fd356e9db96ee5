#pragma once
// Compressed glTF geometry (internal to engine_asset): EXT_meshopt_compression
// bufferViews and KHR_draco_mesh_compression primitives are decoded into plain
// buffers right after tinygltf has parsed the file, so that readAccessor and the
// rest of the loader see an ordinary, uncompressed model.
#include <string>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "core/result.h"

namespace engine::gltf {

// The URI given to a meshopt fallback buffer (EXT_meshopt_compression with
// `fallback: true` and no uri). Such a buffer has no bytes anywhere, but tinygltf
// wants a uri (or, in a GLB, would hand it the BIN chunk), so the raw JSON gets
// this one-byte data: URI; decodeCompressedGeometry empties it again.
inline constexpr const char* kFallbackBufferUri = "data:application/octet-stream;base64,AA==";

// Readies the raw JSON of a compressed model for tinygltf, which (built without
// Draco, as Debian builds it) refuses two things these files legitimately have:
// a meshopt fallback buffer without data (given kFallbackBufferUri), and a Draco
// primitive's index accessor without a bufferView (given the primitive's Draco
// bufferView as a placeholder, which decodeCompressedGeometry replaces). Returns
// whether anything changed (the JSON must then be written back for tinygltf).
bool prepareCompressedJson(nlohmann::json& doc);

// Decodes every EXT_meshopt_compression bufferView and then every
// KHR_draco_mesh_compression primitive of `model` in place; errors name `file`
// and the element ("duck.gltf: mesh 0 primitive 0: KHR_draco_mesh_compression:
// decode failed: ...").
Status decodeCompressedGeometry(tinygltf::Model& model, const std::string& file);

}  // namespace engine::gltf
