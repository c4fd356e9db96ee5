// SceneRenderer's insides, shared by the files that implement it (setup, draw
// lists and passes, shadows, GPU culling; the frame and the public face in
// scene_renderer.cpp). Not part of the engine's interface.
#pragma once

#include "render/scene_renderer.h"

#include <algorithm>
#include <iterator>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <iomanip>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include "gl/bindings.h"
#include "asset/scene_file.h"
#include "core/linear_image.h"
#include "render/character.h"
#include "render/frame_block.h"
#include "render/gpu_cull.h"
#include "render/gpu_scene.h"
#include "render/terrain_cull.h"
#include "scene/terrain_mesh.h"
#include "render/ibl.h"
#include "render/mesh.h"
#include "render/model_renderer.h"
#include "render/draw_items.h"
#include "render/pass_state.h"
#include "render/render_target.h"
#include "render/scene_view.h"
#include "scene/scene.h"
#include "render/textures.h"
#include "terrain/lod.h"
#include "terrain/terrain.h"
#include "terrain/terrain_renderer.h"

namespace engine {

inline constexpr double kSunShadowDistance = 60.0;  // metres of view the sun's map covers
inline constexpr double kSunFarShadowDistance = 4000.0;  // and the far (terrain) map

// A depth map compared in hardware (sampler2DShadow), for the sun: its two maps and
// the near map's copy of its static casters, one format, as glCopyImageSubData needs.
gl::Texture makeSunShadowMap(int size);

// A cube map of the scene seen from a mirror shape's centre.
struct Probe {
  int shape = -1;
  glm::dvec3 center{0.0};
  gl::Texture cube;
};

struct SceneRenderer::Impl {
  // The scene layer's description of what is drawn (its lights included).
  SceneDesc scene;
  RenderDesc render;
  std::string shaderDir;
  std::unique_ptr<ShaderVariants> variants;
  double terrainError = 2.0;                 // the LOD target in pixels (terrain.error_pixels or the override)
  terrain::LodSelection mainTerrain;        // what the last main view drew (mainTerrainSelection)
  std::optional<SkinMode> skinModeOverride;  // every model's, when set
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
  gl::Buffer frameUbo;
  // The scene layer's models, poses and terrain (shared with any other renderer of
  // the same scene) as uploaded.
  std::unique_ptr<GpuScene> gpu;
  FrameBlock frame;
  // HDR target; or, with directOutput, the display values' RGBA8 target, which
  // the fragment shaders write through common/output.glsl and is copied out with
  // no post pass.
  bool directOutput = false;
  int targetWidth = 0, targetHeight = 0;
  gl::Texture hdr;
  gl::Renderbuffer msaaColor, depth;
  gl::Framebuffer drawFbo, resolveFbo;
  // The terrain shaded once a pixel (beginTerrainSurface): its surface at colour
  // attachment 1 of drawFbo, whose depth then has a stencil that marks where the
  // terrain is nearest. Without MSAA, in the main view (probes draw it forward).
  bool deferredTerrain = false;
  gl::Texture terrainSurface;
  // The caller's colour image attached to drawFbo in hdr's place last frame (useColourOf), or 0.
  GLuint borrowedColour = 0;
  bool useColourOf(const gl::FramebufferLayout* caller);
  // The characters shaded once a pixel (drawCharacterSurfaces): their surface at
  // colour attachment 2 of drawFbo (3: the distance, with surfacePosition), and
  // where each group of primitives that share a material is nearest. Without MSAA,
  // in the main view.
  bool deferredCharacters = false;
  bool surfacePosition = false;  // the lighting reads positions (SURFACE_POSITION)
  gl::Texture characterSurface, characterDistance;
  struct SurfaceGroup {
    const CharacterAsset* asset = nullptr;
    int material = -1;
    ShaderVariant shading;  // ShaderVariant::shadingFromSurface of its primitives
  };
  std::vector<SurfaceGroup> surfaceGroups;  // each with its stencil value, in order
  void addSurfaceGroup(const CharacterAsset& asset, int material, const ShaderVariant& forward);
  int surfaceGroupOf(const CharacterAsset& asset, int material, const ShaderVariant& forward) const;  // -1: none
  Status drawCharacterSurfaces(const View& view, const std::vector<DrawItem>& items, const PassInputs& pass,
                               const ItemCommands* commands);
  Status shadeCharacterSurfaces(const View& view, const std::vector<DrawItem>& items);
  // Which pixels a surface group holds: its stencil value where groups share the
  // frame with each other or the terrain's surface; else any depth drawn before
  // the other opaque draws (the surfaces come first).
  bool surfaceStencil() const { return deferredCharacters && (deferredTerrain || surfaceGroups.size() > 1); }
  bool stencilled() const { return deferredTerrain || surfaceStencil(); }
  GLenum depthFormat() const { return stencilled() ? GL_DEPTH32F_STENCIL8 : GL_DEPTH_COMPONENT32F; }
  // Shadows.
  bool sunShadows = false, pointShadows = false;
  int sunLight = -1;
  std::vector<int> pointLights;
  gl::Texture sunShadowMap, pointShadowMap;
  gl::Framebuffer sunShadowFbo, pointShadowFbo;
  // Terrain scenes: a second sun map of the terrain alone, far out (shadows.glsl).
  bool sunFarShadows = false;
  gl::Texture sunShadowMapFar;
  gl::Framebuffer sunShadowFarFbo;
  int sunShadowSize = 0, cubeSize = 0;
  double sunTexelWorld = 0.0;
  // What the sun's maps were last drawn for: while it holds (a still camera), what
  // does not move (shapes, the terrain) is not drawn again. The near map's static
  // casters alone are kept in `sunStaticMap` (made the second still frame, so that
  // a moving camera pays nothing) and copied back under the characters each frame.
  struct SunMapsKey {
    glm::dvec3 eye{0.0};
    glm::mat4 nearBox{0.0f}, farBox{0.0f};
    double fovy = 0.0;
    int viewportHeight = 0;
    bool operator==(const SunMapsKey&) const = default;
  };
  std::optional<SunMapsKey> sunMapsKey;
  gl::Texture sunStaticMap;
  bool sunStaticValid = false;   // sunStaticMap holds the static casters for sunMapsKey
  bool sunMapHasMovers = false;  // sunShadowMap holds characters too
  // The near map's texels the characters may have written in it last, x0 y0 x1 y1
  // (end exclusive): all a kept map's static depth needs back.
  glm::ivec4 sunMoversRect{0};
  // Whether a colour pass's draw may leave the far sun map out (ShaderVariant::
  // nearSunOnly): the frame block's near map covers its world bounds fully.
  bool nearSunCovers(const glm::dvec3& lo, const glm::dvec3& hi) const;
  bool characterNearSunOnly(const CharacterDraw& c) const;
  glm::ivec4 moversFootprint(const std::vector<DrawItem>& movers, const glm::mat4& lightViewProjection) const;
  double pointNear = 0.05, pointFar = 50.0;
  int pcfRadius = 0;
  // Without characters nothing moves: the point light's cube map (which does not
  // depend on the camera) is drawn once and kept.
  bool pointShadowValid = false;
  // Reflection probes: the rasterizer's stand-in for the ray tracer's reflected rays.
  std::vector<Probe> probes;
  int probeSize = 0;
  gl::Renderbuffer probeDepth;
  gl::Framebuffer probeFbo;
  bool probesValid = false;  // static scenes draw their probes once
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
  // Terrain patches hidden by opaque planes are left out (render/plane_occlusion.h).
  bool planeOcclusion = true;
  double planeOcclusionPixelMargin = cull::kPlanePixelMargin;
  std::map<const GpuMesh*, std::uint32_t> shapeClusterBase;
  std::map<const GpuPrimitive*, std::uint32_t> primitiveClusterBase;
  Status makeCuller();
  ItemCommands queueJobs(const std::vector<DrawItem>& items);
  std::vector<IndirectDraw> queueShapeJob(const ShapeDraw& shape);
  std::vector<IndirectDraw> queueCharacterJobs(const DrawItem& item);
  void cullPhase(GpuCuller& with, std::size_t firstJob, std::size_t endJob, const View& view, bool occlusion);
  std::vector<cull::Cluster> terrainPatchBoxes(const terrain::LodSelection& selection) const;
  void drawTerrainCulled(const View& view);
  void hidePatchesBehindPlanes(terrain::LodSelection& selection, const View& view, int skipShape) const;
  Status drawCulled(const View& view, const DrawLists& lists, bool useProbes);
  bool isOccluder(const DrawItem& item) const;
  Status buildOccluderPyramid(const View& view, const std::vector<DrawItem>& occluders);
  terrain::Terrain* terrain = nullptr;  // the scene's, when it has one
  std::unique_ptr<terrain::TerrainRenderer> terrainRenderer;
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
  Status loadTerrain(const std::vector<std::string>& defines);
  terrain::LodSelection selectTerrain(const glm::mat4& cullViewProjection, double fovy, int viewportHeight) const;
  void measureTerrain(double fovy, int viewportHeight);
  TerrainView terrainView(double fovy, int viewportHeight) const;
  void drawTerrain(const View& view, int skipShape);
  terrain::TerrainOutput beginTerrainSurface(const View& view);
  void shadeTerrainSurface(const View& view, const terrain::LodSelection& selection);
  struct SunBox {
    glm::dmat4 view{1.0}, projection{1.0};  // camera-relative world -> the light's clip space
    glm::mat4 shadowMatrix{1.0f};           // camera-relative world -> map [0,1]^3
    double radius = 0.0, texelWorld = 0.0;
  };
  // What a sun map must cover: a sphere, relative to `eye`.
  struct ShadowSphere {
    glm::dvec3 center{0.0};
    double radius = 0.0;
  };
  static ShadowSphere frustumSlice(const glm::dmat4& view, double fovy, double aspect, double nearPlane,
                                   double farPlane);
  SunBox fitSunBox(const ShadowSphere& sphere) const;
  void drawTerrainShadow(const SunBox& box, double fovy, int viewportHeight);
  Status drawSunNear(const SunBox& box, bool still, double fovy, int viewportHeight);
  Status buildVariants();
  void addSurfaceVariants(const std::vector<ShaderVariant>& surfacePasses, std::vector<ShaderVariant>& needed);
  Status makeTarget(int width, int height);
  void setUniforms(const gl::Program& program) const;
  // `surfaces`: deferrable character primitives go to DrawLists::surface.
  Result<DrawLists> collectDraws(const glm::dvec4* planes, bool depthOnly, int skipShape = -1, bool surfaces = false);
  Status collectShapes(const glm::dvec4* planes, bool depthOnly, int skipShape, DrawLists& lists);
  ShaderVariant shapeVariant(const ShapeDraw& shape, bool depthOnly, bool nearSunOnly) const;
  Status collectCharacters(const glm::dvec4* planes, bool depthOnly, bool surfaces, DrawLists& lists);
  Status drawItems(const std::vector<DrawItem>& items, const PassInputs& pass, const ItemCommands* commands = nullptr);
  Status submitItems(const std::vector<DrawItem>& items, const PassInputs& pass, const ItemCommands* commands);
  double animationMs = 0.0;  // the last update's
  void drawShape(const ShapeDraw& shape, const gl::Program& program, const PassInputs& pass,
                 const IndirectDraw* indirect);
  void drawSky(const gl::Program& program, const glm::dmat4& viewProjection, bool sunDisk = true);
  void drawSkyBehind(const View& view);
  Status drawWorld(const View& view, int skipShape, bool useProbes);
  Status makeProbes();
  Status renderProbes(const glm::dvec3& cameraPosition);
  Status renderSunShadow(const ShadowSphere& nearSphere, const ShadowSphere& farSphere, double fovy,
                         int viewportHeight);
  Status renderPointShadow(const glm::dvec3& cameraPosition);
  Status renderFrame(const Camera& camera, int width, int height);
  bool needsNoHdrTarget(const Scene& source) const;
  // What the fragment shaders of a directOutput scene are built with (common/output.glsl).
  std::vector<std::string> displayDefines() const;
  void makeDisplayTable();
  Status makePost();
  void fillFrame(const glm::dvec3& cameraPosition, const glm::mat4& viewProjection);
};

}  // namespace engine
