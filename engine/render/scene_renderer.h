#pragma once
// Renders a SceneDesc: builds only the passes and shader variants the scene needs
// (sun shadow map, point-light cube shadow, sky, opaque, post), draws into an HDR
// target (multisampled and/or supersampled as the render settings say), then tone
// maps into whatever framebuffer is bound. Reverse-Z depth and camera-relative
// positions keep scenes far from the origin free of depth fighting and jitter.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "asset/scene_desc.h"
#include "core/linear_image.h"
#include "core/result.h"
#include "anim/clip.h"
#include "render/camera.h"
#include "render/model_renderer.h"
#include "render/plane_occlusion.h"
#include "render/scene_stats.h"
#include "scene/model_asset.h"

namespace engine {

class AtmosphereTables;

namespace terrain {
struct LodSelection;
}

class CharacterInstance;
class EnvironmentLighting;
class Scene;

// What scene.frag writes in place of the shaded colour (the viewer's debug views,
// as the Khronos Sample Viewer has them): the shading normal (world, mapped to 0..1),
// TEXCOORD_0 (fract), the base colour, metallic, roughness, occlusion, emission or
// alpha, as they are: data channels arrive as their values in bytes, colours as
// colours, with no exposure or tone map.
enum class DebugView { None, Normal, Uv, BaseColor, Metallic, Roughness, Occlusion, Emissive, Alpha };
// "none", "normal", "uv", "basecolor", "metallic", "roughness", "occlusion",
// "emissive", "alpha".
const char* debugViewName(DebugView view);
std::optional<DebugView> parseDebugView(const std::string& name);
// Every view's name, ", " between them (for help and error messages).
std::string debugViewList();

struct SceneRenderOptions {
  std::string shaderDir;
  int msaaOverride = 0;        // > 0 replaces the scene's render.msaa
  int supersampleOverride = 0;
  int shadowMapOverride = 0;
  int pcfKernelOverride = 0;   // odd width; 1 = hard
  int reflectionProbeOverride = -1;  // >= 0 replaces render.reflection_probe (0 = off)
  std::optional<Ambient> ambientOverride;  // replaces render.ambient (PBR scenes)
  int iblSizeOverride = 0;                 // > 0 replaces render.ibl_size
  std::optional<Skinning> skinningOverride;  // replaces render.skinning
  double terrainErrorOverride = 0.0;         // > 0 replaces terrain.error_pixels (the LOD target)
  std::optional<double> lodPixelsOverride;   // replaces render.lod_pixels (models' levels of detail)
  std::optional<bool> gpuCullingOverride;    // replaces render.gpu_culling (render/gpu_cull.h)
  // Tests only: GPU culling's depth margin (cull::View::depthMargin); a negative
  // one culls what is in front, and the culled image must then differ.
  float gpuCullingDepthMargin = cull::kDepthMargin;
  // Tests only: false draws the terrain patches an opaque plane hides (the
  // reference the occlusion is tested against, render/plane_occlusion.h); the
  // occlusion's pixel margin, whose negative values hide what shows.
  bool planeOcclusion = true;
  double planeOcclusionPixelMargin = cull::kPlanePixelMargin;
  // Replaces every model's skinning (lbs, dqs, none: the bind pose).
  std::optional<SkinMode> skinModeOverride;
  // Replace render.shading, render.exposure (> 0), render.tonemap, render.output.
  std::optional<Shading> shadingOverride;
  float exposureOverride = 0.0f;
  std::optional<ToneMap> toneMapOverride;
  std::optional<OutputCurve> outputOverride;
  // How the rasterizer's poses interpolate rotation keys: slerp (exact) or nlerp.
  QuatInterpolation rotations = QuatInterpolation::Slerp;
  DebugView debugView = DebugView::None;
  // Keeps the HDR target and the post pass where the scene could do without them
  // (directOutput in scene_renderer.cpp): the reference that path is tested against.
  bool hdrTarget = false;
  // Shades the terrain where its patches are drawn, rather than once a pixel from
  // the surface they leave (SceneRenderer's deferred terrain, the default without
  // MSAA): the reference that pass is tested against, and its cost's.
  bool forwardTerrain = false;
  // Shades characters where their triangles are drawn, rather than once a pixel
  // from the surface they leave (SceneRenderer's deferred characters, the default
  // without MSAA): likewise.
  bool forwardCharacters = false;
};

class SceneRenderer {
 public:
  // Uploads what the scene layer loaded (scene/scene.h: models, terrain), loads the
  // textures and builds the programs. Needs a current context. The renderer keeps
  // `scene` and draws its poses. `sharing`: a renderer of the same scene (the one
  // the trade panel's knobs replace) whose uploads this one shares, where the
  // options upload the same (the skinning, the levels of detail, the probes).
  static Result<std::unique_ptr<SceneRenderer>> create(std::shared_ptr<Scene> scene,
                                                       const SceneRenderOptions& options,
                                                       const SceneRenderer* sharing = nullptr);
  // Scene::load (clip names are checked: "demo.json: /models/2/clip: no clip ..."),
  // then the above.
  static Result<std::unique_ptr<SceneRenderer>> create(const SceneDesc& scene, const SceneRenderOptions& options);
  ~SceneRenderer();

  // Poses the scene at scene time `time` (seconds; Scene::update, which does
  // nothing when another renderer of the same scene has posed it at that time) and
  // takes its poses.
  Status update(double time);
  // Poses instance `instance` with a pose made elsewhere (Scene::setPose: the
  // viewer's player), in the scene and in what this renderer draws.
  void setPose(int instance, const Pose& pose);
  // Draws the frame into the framebuffer bound now, of `width` x `height` pixels.
  Status render(const Camera& camera, int width, int height);
  // The last frame's linear radiance (OutputPass::readLinear): needs the HDR target,
  // which a renderer made with options.hdrTarget always has.
  Result<FloatImage> readLinear() const;

  // The camera the scene file describes, for the window's controls.
  Camera initialCamera() const;
  // "passes: ...\nvariants: ..." for demo --describe.
  std::string describe() const;
  const SceneStats& stats() const { return stats_; }
  // Triangles the GL processed in the last frame, every pass included (a
  // GL_PRIMITIVES_GENERATED query). Waits for the frame: for benchmarks and tools.
  long long lastFrameTriangles() const;
  // GPU culling's counters of the last frame, read back (waits): for benchmarks,
  // tools and tests. All zero with culling off.
  CullStats cullStats() const;
  // Every pass's GPU time, in the order the frame draws them.
  std::vector<PassTime> passTimes() const;
  const SceneDesc& scene() const;
  // The time of day, with a planet's atmosphere: the sun's elevation in degrees
  // above the horizontal, its azimuth kept. Turns the shaded light, its shadows and
  // the sky, whose tables and environment are rebuilt at the next frame. NaN
  // without a sun.
  double sunElevationDegrees() const;
  void setSunElevation(double degrees);
  // The atmosphere's tables (render/atmosphere_tables.h), null without an
  // atmosphere. For tests and tools.
  const AtmosphereTables* atmosphereTables() const;
  // The PBR ambient's image-based lighting (render/ibl.h): null for the hemisphere
  // ambient and classic shading. For tests and tools.
  const EnvironmentLighting* environmentLighting() const;
  std::vector<CharacterInstance*> characters();
  // The terrain patches the last frame's main view drew (after culling), or null
  // without terrain: for tests comparing it with the tracers' terrain.
  const terrain::LodSelection* mainTerrainSelection() const;

 private:
  struct Impl;
  explicit SceneRenderer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  SceneStats stats_;
};

}  // namespace engine
