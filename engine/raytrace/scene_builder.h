#pragma once
// The ray tracer's view of a scene file at one time: the analytic primitives and
// lights of the SceneDesc, plus every glTF model posed at that time and skinned on
// the CPU with the same jobs and palettes the rasterizer uses (anim/jobs.h), as
// triangle meshes in the BVH.
#include "asset/scene_desc.h"
#include "core/image.h"
#include "core/result.h"
#include "raytrace/integrator.h"
#include "raytrace/rt_scene.h"

namespace engine::rt {

struct SceneBuildStats {
  int meshes = 0;
  int triangles = 0;
  double skinSeconds = 0.0;
  double bvhSeconds = 0.0;
};

// Errors name the scene file and the model element, like the rasterizer's. The
// terrain is triangulated exactly as the rasterizer draws it for this camera and
// an image `viewportHeight` pixels high (the same CDLOD selection and morph).
Result<RtScene> buildRtScene(const SceneDesc& scene, double time, int viewportHeight = 720,
                             SceneBuildStats* stats = nullptr);

struct RaytraceRun {
  Image image;  // tone mapped and encoded as the scene's render settings say
  RenderResult result;
  SceneBuildStats build;
};

// The whole ray-traced frame: scene at `time`, rendered, converted to 8 bits.
Result<RaytraceRun> raytraceScene(const SceneDesc& scene, double time, const RenderSettings& settings);

}  // namespace engine::rt
