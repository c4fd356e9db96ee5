#pragma once
// `demo --mode raytrace|pathtrace --describe`: what the tracer builds and pays for to
// draw a scene with these settings (the rasterizer's --describe lists its passes and
// shader variants): its integrator and settings, then the scene's shapes, BVH groups,
// lights, materials, textures and environment.
#include <string>

#include "raytrace/render_types.h"
#include "raytrace/rt_scene.h"

namespace engine::rt {

std::string describe(const RtScene& scene, const RenderSettings& settings);

}  // namespace engine::rt
