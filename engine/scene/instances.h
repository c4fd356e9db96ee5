#pragma once
// Where a scene file's model instances are in their clips at scene time t: both
// renderers pose by it, so a character stands the same in the rasterized and the
// traced frame, and a frame never depends on the frames before it.
#include "asset/scene_desc.h"

namespace engine {

// The instance's clip time, before wrapping into the clip: start + t * speed.
inline double clipTimeAt(const ModelDesc& instance, double sceneTime) {
  return instance.start + sceneTime * instance.speed;
}

}  // namespace engine
