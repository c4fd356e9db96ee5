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
#include "render/terrain_cull.h"
#include "scene/terrain_mesh.h"
#include "render/ibl.h"
#include "render/mesh.h"
#include "render/model_renderer.h"
#include "render/draw_items.h"
#include "render/pass_state.h"
#include "render/render_target.h"
#include "scene/scene.h"
#include "render/textures.h"
#include "terrain/lod.h"
#include "terrain/terrain.h"
#include "terrain/terrain_renderer.h"

namespace engine {

inline constexpr double kSunShadowDistance = 60.0;  // metres of view the sun's map covers
inline constexpr double kSunFarShadowDistance = 4000.0;  // and the far (terrain) map

// GL's cube face order, and the view axes that put each face's image where the
// cube map's lookup expects it.
inline constexpr glm::dvec3 kCubeFaceDirections[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
inline constexpr glm::dvec3 kCubeFaceUps[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};

// A unit shape placed in the world, with a bounding sphere for culling
// (radius < 0: unbounded, never culled).
struct ShapeDraw {
  const GpuMesh* mesh = nullptr;
  glm::vec2 uvScale{1.0f};  // texture repeats across the shape
  glm::dmat4 world{1.0};
  int material = 0;
  glm::dvec3 center{0.0};
  double radius = -1.0;
  glm::dvec3 lo{0.0}, hi{0.0};  // world bounds: its mesh's, placed
  bool twoSided = false;
  int probe = -1;  // reflection probe of a mirror shape
};

// Where a scene pass looks from: the camera, or one face of a reflection probe.
struct View {
  glm::dmat4 viewProjection{1.0};
  glm::dvec4 planes[6];
  double fovy = 1.0;
  int width = 1, height = 1;
  bool mirrored = false;  // a left-handed camera: faces wind the other way
  // The camera's own view: only it copies its opaque pass for transmissive surfaces
  // to refract (probe views refract the camera's last copy).
  bool main = false;
};

// What the draws of one pass share besides the items themselves.
struct PassInputs {
  bool depthOnly = false;
  glm::mat4 lightViewProjection{1.0f};  // shadow passes
  glm::mat4 viewProjection{1.0f};
  bool useProbes = false;  // mirrors show their reflection probe
  bool surface = false;    // the deferred characters' surface pass (drawCharacterSurfaces)
};

// GPU culling's commands for each item of a draw list, aligned with it: one per
// instance drawn (a shape's one, a glTF node's mesh instances); empty for a plain
// draw (culling off, or a primitive without clusters).
using ItemCommands = std::vector<std::vector<IndirectDraw>>;

// A depth map compared in hardware (sampler2DShadow), for the sun: its two maps and
// the near map's copy of its static casters, one format, as glCopyImageSubData needs.
gl::Texture makeSunShadowMap(int size);

// The opaque and the blended draws of one view; the opaque ones of transmissive
// materials (KHR_materials_transmission) apart, as they refract the others.
struct DrawLists {
  std::vector<DrawItem> opaque, transmissive, blend;
  // Opaque character primitives shaded once a pixel (deferredCharacters), apart.
  std::vector<DrawItem> surface;
  bool refracts = false;  // some item, opaque or blended, is transmissive
};

// The stencil of a frame with deferred surfaces: 1 marks the deferred terrain's
// pixels (beginTerrainSurface), each surface group of the characters its own value
// from 2 up (drawCharacterSurfaces).
inline constexpr int kTerrainStencil = 1;
inline constexpr int kFirstSurfaceStencil = 2;
inline constexpr std::size_t kMaxSurfaceGroups = 256 - kFirstSurfaceStencil;

// A cube map of the scene seen from a mirror shape's centre.
struct Probe {
  int shape = -1;
  glm::dvec3 center{0.0};
  gl::Texture cube;
};

// A scene instance (scene/scene.h) on the GPU: its pose is the scene's, copied in
// by update; `world`, the bounds and the file's entry are the instance's.
struct CharacterDraw {
  std::unique_ptr<CharacterInstance> instance;
  glm::dmat4 world{1.0};
  ModelDesc desc;
  glm::dvec3 localCenter{0.0};
  double localRadius = 1.0;
};

inline SkinMode skinModeOf(const ModelDesc& desc) {
  return desc.unskinned ? SkinMode::None : desc.dualQuat ? SkinMode::DualQuat : SkinMode::Linear;
}

// Reverse-Z projection (near maps to 1, far to 0) for GL_ZERO_TO_ONE clip space:
// float depth then spends its precision evenly across distance.
inline glm::dmat4 reverseZProjection(double fovyRadians, double aspect, double nearPlane, double farPlane) {
  return glm::perspectiveRH_ZO(fovyRadians, aspect, farPlane, nearPlane);
}

// The six planes of a view-projection (Gribb-Hartmann), normalised, inside >= 0.
inline void frustumPlanes(const glm::dmat4& m, glm::dvec4 planes[6]) {
  const glm::dvec4 row0(m[0][0], m[1][0], m[2][0], m[3][0]);
  const glm::dvec4 row1(m[0][1], m[1][1], m[2][1], m[3][1]);
  const glm::dvec4 row2(m[0][2], m[1][2], m[2][2], m[3][2]);
  const glm::dvec4 row3(m[0][3], m[1][3], m[2][3], m[3][3]);
  planes[0] = row3 + row0;
  planes[1] = row3 - row0;
  planes[2] = row3 + row1;
  planes[3] = row3 - row1;
  planes[4] = row2;         // zero-to-one depth: z >= 0
  planes[5] = row3 - row2;  // z <= w
  for (int i = 0; i < 6; ++i) planes[i] /= glm::length(glm::dvec3(planes[i]));
}

struct SceneRenderer::Impl {
  // What is drawn: the scene layer's models, poses and terrain (shared with any
  // other renderer of the same scene); `scene` is its description.
  std::shared_ptr<Scene> source;
  SceneDesc scene;
  RenderDesc render;
  std::string shaderDir;
  std::unique_ptr<ShaderVariants> variants;
  // The skin cache's compute programs, made with the first instance that uses the
  // cache (usesSkinCache; declared before the characters, which point at it).
  std::unique_ptr<SkinPrograms> skinPrograms;
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
  gl::Texture skyImage;  // the sky's lat-long image, when the scene has one
  // The PBR ambient (render/ibl.h); built at load for Ambient::Sh and ::Ibl only.
  Ambient ambient = Ambient::Hemisphere;
  int iblSize = 0;
  std::optional<EnvironmentLighting> environmentLighting;
  double iblMilliseconds = 0.0;  // its one-time cost, GL work finished
  gl::VertexArray emptyVao;
  gl::Buffer frameUbo;
  std::unique_ptr<GpuMesh> sphere, cube, quad;
  std::vector<ShapeDraw> shapes;
  std::vector<gl::Texture> materialTextures;  // empty texture = none
  std::vector<CharacterDraw> characters;
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
  std::pair<glm::dvec3, double> placedSphere(const CharacterDraw& c) const;
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
  bool blendPass = false;  // some model has a BLEND material
  // Some model has a transmissive material: the opaque pass is copied, mipmapped,
  // for it to refract (common/transmission.glsl).
  bool transmissionPass = false;
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
  glm::dvec3 eye{0.0};  // camera position of the frame being drawn
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

  Status init(const SceneRenderOptions& options);
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
  Status loadMaterials();
  Status loadModels();
  void addShapes();
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
  std::size_t itemTriangles(const DrawItem& item) const;
  Status submitItems(const std::vector<DrawItem>& items, const PassInputs& pass, const ItemCommands* commands);
  double animationMs = 0.0;  // the last update's
  void drawShape(const ShapeDraw& shape, const gl::Program& program, const PassInputs& pass,
                 const IndirectDraw* indirect);
  glm::mat4 shapeModel(const ShapeDraw& shape) const;
  void drawSky(const gl::Program& program, const glm::dmat4& viewProjection, bool sunDisk = true);
  void drawSkyBehind(const View& view);
  Status drawWorld(const View& view, int skipShape, bool useProbes);
  Status makeProbes();
  Status renderProbes(const glm::dvec3& cameraPosition);
  void placeCharacters(const glm::dvec3& cameraPosition);
  void chooseLevelsOfDetail(const glm::dvec3& cameraPosition, double fovy, int height, double nearPlane);
  std::string describeLevelsOfDetail() const;
  Status renderSunShadow(const ShadowSphere& nearSphere, const ShadowSphere& farSphere, double fovy,
                         int viewportHeight);
  Status renderPointShadow(const glm::dvec3& cameraPosition);
  Status renderFrame(const Camera& camera, int width, int height);
  Status deformCharacters();
  bool needsNoHdrTarget() const;
  // What the fragment shaders of a directOutput scene are built with (common/output.glsl).
  std::vector<std::string> displayDefines() const;
  void makeDisplayTable();
  Status makePost();
  bool usesSkinCache(const ModelData& model, const ModelDesc& desc) const;
  std::string describeSkinCache() const;
  void fillFrame(const glm::dvec3& cameraPosition, const glm::mat4& viewProjection);
};

}  // namespace engine
