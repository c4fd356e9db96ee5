#pragma once
// The glTF loader's limits, apart from the loader so that its parts (accessors,
// compressed meshes) read them without including the loader.
#include <cstddef>
#include <cstdint>

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

}  // namespace engine
