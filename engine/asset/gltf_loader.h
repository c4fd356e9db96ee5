#pragma once
// glTF 2.0 (.gltf with external or embedded buffers, .glb) into ModelData.
// The file is untrusted: every problem comes back as an Error naming the file and
// the element ("hero.glb: skin 0: joint 7 has no node"); nothing aborts.
#include <cstdint>
#include <span>
#include <string>

#include "asset/model_data.h"
#include "core/result.h"

namespace engine {

// Limits that keep a hostile file from exhausting memory.
inline constexpr std::uint64_t kMaxModelFileBytes = 512ull * 1024 * 1024;
inline constexpr std::size_t kMaxSkinJoints = 65536;
inline constexpr std::size_t kMaxNodes = 1u << 20;
inline constexpr std::size_t kMaxAccessorElements = 1u << 26;
// Morph target displacements of one attribute of one primitive (targets x
// vertices): many targets may name one small file's zero-filled sparse accessor.
inline constexpr std::size_t kMaxMorphDeltas = 1u << 24;
// EXT_mesh_gpu_instancing instances of one node (a mat4 each, and as many draws).
inline constexpr std::size_t kMaxNodeInstances = 1u << 20;

// Refuses URIs that leave the model's folder ("..", absolute paths, other
// schemes than data:). Missing or undecodable images only warn and get a 1x1
// white fallback; missing buffers are errors. `scene` chooses the glTF scene drawn
// (-1: the file's default, else its first; one it lacks is an error): nodes outside
// it keep their place and animation but carry no mesh, light or camera.
Result<ModelData> loadGltf(const std::string& path, int scene = -1);

// The same loader on bytes already in memory (.glb or .gltf text); `name` stands
// for the file in messages. Only data: URIs are followed: a buffer that names a
// file is an error, an image that names one gets the fallback.
Result<ModelData> loadGltfFromMemory(std::span<const unsigned char> bytes, const std::string& name);

}  // namespace engine
