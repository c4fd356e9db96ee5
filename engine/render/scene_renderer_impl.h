// SceneRenderer's insides: the passes a scene needs, made at load
// (scene_renderer_setup.cpp) and sequenced each frame (scene_renderer.cpp). Each
// pass (render/*_pass.h) owns its GL resources and state and draws the GPU scene
// (render/gpu_scene.h) through each view's draw lists (render/scene_draws.h). Not
// part of the engine's interface.
#pragma once

#include "render/scene_renderer.h"

#include <memory>

#include "gl/resources.h"
#include "render/character_surface_pass.h"
#include "render/frame_uniforms.h"
#include "render/gpu_cull_pass.h"
#include "render/gpu_scene.h"
#include "render/output_pass.h"
#include "render/pass_timers.h"
#include "render/point_shadow_pass.h"
#include "render/reflection_probe_pass.h"
#include "render/scene_draws.h"
#include "render/sky_pass.h"
#include "render/sun_shadow_pass.h"
#include "render/terrain_pass.h"
#include "render/transmission_pass.h"
#include "render/world_pass.h"

namespace engine {

struct SceneRenderer::Impl {
  // The scene file's description of what is drawn (its lights are read from the
  // scene's environment instead, scene/environment.h), and the settings it is drawn
  // with after the options' overrides.
  SceneDesc scene;
  RenderDesc render;
  QuatInterpolation rotations = QuatInterpolation::Slerp;  // how the scene's poses interpolate
  DebugView debugView = DebugView::None;
  Ambient ambient = Ambient::Hemisphere;  // the PBR ambient
  int pcfRadius = 0;                      // the shadows' filter
  SceneStats* stats = nullptr;            // the SceneRenderer's
  // The scene layer's models, poses and terrain (shared with any other renderer of
  // the same scene) as uploaded, each view's draws of them, and the frame block
  // their programs read.
  std::shared_ptr<GpuScene> gpu;
  std::unique_ptr<SceneDraws> draws;
  std::unique_ptr<FrameUniforms> frame;
  // The passes, in about the order a frame draws them; null where the scene needs
  // none.
  std::unique_ptr<PointShadowPass> point;
  std::unique_ptr<ReflectionProbePass> probes;
  std::unique_ptr<SunShadowPass> sun;
  std::unique_ptr<SkyPass> sky;
  std::unique_ptr<TerrainPass> terrain;
  std::unique_ptr<CharacterSurfacePass> surfaces;
  std::unique_ptr<TransmissionPass> transmission;
  std::unique_ptr<GpuCullPass> culling;
  std::unique_ptr<WorldPass> world;
  std::unique_ptr<OutputPass> output;
  PassTimers timers;
  gl::Query primitives;      // triangles of the whole frame
  double animationMs = 0.0;  // the last update's

  // `shared`: another renderer's GPU scene, taken where it is of `source` and
  // uploaded as these options would.
  Status init(std::shared_ptr<Scene> source, const SceneRenderOptions& options, std::shared_ptr<GpuScene> shared);
  // Whether the frame can skip the HDR target and the post pass (OutputPass::direct).
  bool needsNoHdrTarget(const Scene& source) const;
  // What the draws read of the passes made (SceneDraws::link).
  DrawSources drawSources() const;
  // The frame's depth has a stencil where a deferred surface marks its pixels.
  GLenum depthFormat() const;
  Status renderFrame(const Camera& camera, int width, int height);
};

}  // namespace engine
