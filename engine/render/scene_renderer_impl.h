// SceneRenderer's insides, shared by the files that implement it (setup, the
// world of one view, GPU culling; the frame and the public face in
// scene_renderer.cpp). Each pass is an object of its own (render/*_pass.h) over
// the GPU scene (render/gpu_scene.h) and its draw lists (render/scene_draws.h).
// Not part of the engine's interface.
#pragma once

#include "render/scene_renderer.h"

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gl/resources.h"
#include "render/character_surface_pass.h"
#include "render/frame_uniforms.h"
#include "render/gpu_cull.h"
#include "render/gpu_scene.h"
#include "render/ibl.h"
#include "render/point_shadow_pass.h"
#include "render/reflection_probe_pass.h"
#include "render/scene_draws.h"
#include "render/scene_view.h"
#include "render/sun_shadow_pass.h"
#include "render/terrain_pass.h"

namespace engine {

struct SceneRenderer::Impl {
  // The scene layer's description of what is drawn (its lights included).
  SceneDesc scene;
  RenderDesc render;
  std::string shaderDir;
  QuatInterpolation rotations = QuatInterpolation::Slerp;
  DebugView debugView = DebugView::None;
  // sky: linear radiance (the HDR target, the environment cube); skyDisplay: with
  // directOutput, the view's display values.
  gl::Program sky, skyDisplay, post;
  // The display curve's table (core/srgb_curve.h) for every program that writes
  // display values; none under the gamma 2.2 curve.
  gl::Buffer displayTableTexels;
  gl::Texture displayTable;
  // The PBR ambient (render/ibl.h); built at load for Ambient::Sh and ::Ibl only.
  Ambient ambient = Ambient::Hemisphere;
  int iblSize = 0;
  std::optional<EnvironmentLighting> environmentLighting;
  double iblMilliseconds = 0.0;  // its one-time cost, GL work finished
  gl::VertexArray emptyVao;
  // The scene layer's models, poses and terrain (shared with any other renderer of
  // the same scene) as uploaded, and each view's draws of them.
  std::unique_ptr<GpuScene> gpu;
  std::unique_ptr<SceneDraws> draws;
  CompiledLights lights;
  std::unique_ptr<FrameUniforms> frame;
  // HDR target; or, with directOutput, the display values' RGBA8 target, which
  // the fragment shaders write through common/output.glsl and is copied out with
  // no post pass.
  bool directOutput = false;
  int targetWidth = 0, targetHeight = 0;
  gl::Texture hdr;
  gl::Renderbuffer msaaColor, depth;
  gl::Framebuffer drawFbo, resolveFbo;
  // The caller's colour image attached to drawFbo in hdr's place last frame (useColourOf), or 0.
  GLuint borrowedColour = 0;
  bool useColourOf(const gl::FramebufferLayout* caller);
  // The passes the scene needs; null where it needs none.
  std::unique_ptr<TerrainPass> terrain;
  std::unique_ptr<CharacterSurfacePass> surfaces;
  std::unique_ptr<SunShadowPass> sun;
  std::unique_ptr<PointShadowPass> point;
  std::unique_ptr<ReflectionProbePass> probes;
  int pcfRadius = 0;
  // The frame's depth has a stencil where a deferred surface marks its pixels.
  bool stencilled() const { return (terrain && terrain->deferred()) || (surfaces && surfaces->stencil()); }
  GLenum depthFormat() const { return stencilled() ? GL_DEPTH32F_STENCIL8 : GL_DEPTH_COMPONENT32F; }
  // Some model has a transmissive material: the opaque pass is copied, mipmapped,
  // for it to refract (common/transmission.glsl).
  gl::Texture transmissionSource;
  gl::Framebuffer transmissionFbo;
  void copyTransmissionSource();
  // GPU culling (render.gpu_culling, render/gpu_cull.h): made at load with every
  // mesh's clusters; where each mesh's clusters start in its table.
  std::unique_ptr<GpuCuller> culler;
  std::unique_ptr<GpuCuller> terrainCuller;  // the terrain's patches, a table of their own each frame
  std::unique_ptr<HiZPyramid> hiz;
  float cullDepthMargin = cull::kDepthMargin;
  std::map<const GpuMesh*, std::uint32_t> shapeClusterBase;
  std::map<const GpuPrimitive*, std::uint32_t> primitiveClusterBase;
  Status makeCuller();
  ItemCommands queueJobs(const std::vector<DrawItem>& items);
  std::vector<IndirectDraw> queueShapeJob(const ShapeDraw& shape);
  std::vector<IndirectDraw> queueCharacterJobs(const DrawItem& item);
  void cullPhase(GpuCuller& with, std::size_t firstJob, std::size_t endJob, const View& view, bool occlusion);
  std::vector<cull::Cluster> terrainPatchBoxes(const terrain::LodSelection& selection) const;
  void drawTerrainCulled(const View& view);
  Status drawCulled(const View& view, const DrawLists& lists, bool useProbes);
  bool isOccluder(const DrawItem& item) const;
  Status buildOccluderPyramid(const View& view, const std::vector<DrawItem>& occluders);
  SceneStats* stats = nullptr;
  gl::Query primitives;  // triangles of the whole frame
  bool primitivesValid = false;
  // GPU time per pass: one query each, begun only once its last result is read.
  struct PassTimer {
    std::string pass;
    gl::Query query;
    bool pending = false;
    double ms = 0.0;
  };
  std::vector<PassTimer> timers;
  int activeTimer = -1;
  void beginTimer(const std::string& pass);
  void endTimer();
  void collectTimers();

  Status init(std::shared_ptr<Scene> source, const SceneRenderOptions& options);
  Status makeSky();
  Status makeEnvironmentLighting();
  Status makeTarget(int width, int height);
  double animationMs = 0.0;  // the last update's
  void drawSky(const gl::Program& program, const glm::dmat4& viewProjection, bool sunDisk = true);
  void drawSkyBehind(const View& view);
  Status drawWorld(const View& view, int skipShape, bool useProbes);
  Status renderFrame(const Camera& camera, int width, int height);
  bool needsNoHdrTarget(const Scene& source) const;
  // What the fragment shaders of a directOutput scene are built with (common/output.glsl).
  std::vector<std::string> displayDefines() const;
  void makeDisplayTable();
  Status makePost();
};

}  // namespace engine
