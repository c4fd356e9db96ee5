#pragma once
// glTF 2.0 (.gltf with external or embedded buffers, .glb) into ModelData.
// The file is untrusted: every problem comes back as an Error naming the file and
// the element ("hero.glb: skin 0: joint 7 has no node"); nothing aborts.
#include <cstdint>
#include <span>
#include <string>

#include "asset/gltf_limits.h"
#include "asset/model_data.h"
#include "core/result.h"

namespace engine {

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
