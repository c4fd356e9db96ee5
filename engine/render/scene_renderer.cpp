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

#include "gl/bindings.h"
#include "asset/material_texture.h"
#include "asset/scene_file.h"
#include "core/linear_image.h"
#include "render/character.h"
#include "render/frame_block.h"
#include "render/gpu_cull.h"
#include "render/terrain_cull.h"
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
namespace {

constexpr double kSunShadowDistance = 60.0;  // metres of view the sun's map covers
constexpr double kSunFarShadowDistance = 4000.0;  // and the far (terrain) map
constexpr int kMaxCubeShadowSize = 1024;
constexpr int kMaxReflectionProbes = 4;
constexpr double kProbeNear = 0.01;

// GL's cube face order, and the view axes that put each face's image where the
// cube map's lookup expects it.
constexpr glm::dvec3 kCubeFaceDirections[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
constexpr glm::dvec3 kCubeFaceUps[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};

// A unit shape placed in the world, with a bounding sphere for culling
// (radius < 0: unbounded, never culled).
struct ShapeDraw {
  const GpuMesh* mesh = nullptr;
  glm::vec2 uvScale{1.0f};  // texture repeats across the shape
  glm::dmat4 world{1.0};
  int material = 0;
  glm::dvec3 center{0.0};
  double radius = -1.0;
  bool twoSided = false;
  int probe = -1;  // reflection probe of a mirror shape
};

// Where a scene pass looks from: the camera, or one face of a reflection probe.
struct View {
  glm::dmat4 viewProjection{1.0};
  glm::dvec4 planes[6];
  double fovy = 1.0;
  int height = 1;
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
};

// GPU culling's commands for each item of a draw list, aligned with it: one per
// instance drawn (a shape's one, a glTF node's mesh instances); empty for a plain
// draw (culling off, or a primitive without clusters).
using ItemCommands = std::vector<std::vector<IndirectDraw>>;

// The opaque and the blended draws of one view; the opaque ones of transmissive
// materials (KHR_materials_transmission) apart, as they refract the others.
struct DrawLists {
  std::vector<DrawItem> opaque, transmissive, blend;
  bool refracts = false;  // some item, opaque or blended, is transmissive
};

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

// common/output.glsl's displayValue on the CPU (the direct path's clear colour).
glm::vec3 displayValue(glm::vec3 c, OutputCurve curve) {
  c = glm::clamp(c, 0.0f, 1.0f);
  if (curve == OutputCurve::Gamma22) return glm::pow(c, glm::vec3(1.0f / 2.2f));
  const glm::vec3 high = 1.055f * glm::pow(c, glm::vec3(1.0f / 2.4f)) - 0.055f;
  return glm::mix(c * 12.92f, high, glm::step(glm::vec3(0.0031308f), c));
}

// The direct path draws into the caller's framebuffer itself, with no target of its
// own and no copy, when that is a single-sample framebuffer object of the frame's
// size with 8-bit normalised colour (RGBA8 or SRGB8_ALPHA8: with GL_FRAMEBUFFER_SRGB
// off both store the shader's bytes as they are) and 32-bit float depth (the
// reverse-Z depth every pass tests against; fixed-point depth would move bytes).
// On llvmpipe the copy was a shader pass over every pixel: about 3 ms at 1280x720.
bool takesDirectFrame(const gl::FramebufferLayout& l, int width, int height) {
  const bool color8 = l.colorType == GL_UNSIGNED_NORMALIZED && l.colorBits[0] == 8 && l.colorBits[1] == 8 &&
                      l.colorBits[2] == 8 && l.colorBits[3] == 8;
  return l.samples == 0 && l.width == width && l.height == height && color8 && l.depthBits == 32 &&
         l.depthType == GL_FLOAT;
}

SkinMode skinModeOf(const ModelDesc& desc) {
  return desc.unskinned ? SkinMode::None : desc.dualQuat ? SkinMode::DualQuat : SkinMode::Linear;
}

// View rotation from a forward and an up vector; a left-handed scene (the course's
// room) puts +x on the right when looking along +z, which mirrors GL's convention.
glm::dmat4 viewRotation(const glm::dvec3& forward, const glm::dvec3& upHint, bool leftHanded) {
  const glm::dvec3 f = glm::normalize(forward);
  const glm::dvec3 r = glm::normalize(leftHanded ? glm::cross(upHint, f) : glm::cross(f, upHint));
  const glm::dvec3 u = leftHanded ? glm::cross(f, r) : glm::cross(r, f);
  glm::dmat4 v(1.0);
  for (int i = 0; i < 3; ++i) {
    v[i][0] = r[i];
    v[i][1] = u[i];
    v[i][2] = -f[i];
  }
  return v;
}

// Reverse-Z projection (near maps to 1, far to 0) for GL_ZERO_TO_ONE clip space:
// float depth then spends its precision evenly across distance.
glm::dmat4 reverseZProjection(double fovyRadians, double aspect, double nearPlane, double farPlane) {
  return glm::perspectiveRH_ZO(fovyRadians, aspect, farPlane, nearPlane);
}

// A depth map compared in hardware (sampler2DShadow), for the sun.
gl::Texture makeSunShadowMap(int size) {
  gl::Texture map = gl::Texture::create2D(GL_DEPTH_COMPONENT32F, size, size, 1);
  map.parameter(GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  map.parameter(GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  map.parameter(GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  map.parameter(GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  map.parameter(GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  map.parameter(GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return map;
}

// The sky's lat-long image as half floats, mipmapped, repeating in u and clamped in
// v. Rows go up as the image stores them (top first), so texture t = v: t = 0 is the
// zenith, as common/latlong.glsl has it. Radiance past half's largest value (65504)
// is clamped rather than left to the driver's conversion. RGBA16F, not RGB16F: it is
// colour-renderable everywhere, which glGenerateMipmap may demand, and drivers
// store RGB16F as four channels anyway; the upload's RGB leaves alpha 1. A row of
// 12-byte texels meets any unpack alignment up to 4.
gl::Texture uploadSkyImage(const FloatImage& image) {
  gl::Texture texture = gl::Texture::create2D(GL_RGBA16F, image.width, image.height, 0);
  std::vector<float> clamped(image.rgb.size());
  std::transform(image.rgb.begin(), image.rgb.end(), clamped.begin(),
                 [](float v) { return std::clamp(v, 0.0f, 65504.0f); });
  glTextureSubImage2D(texture.id(), 0, 0, 0, image.width, image.height, GL_RGB, GL_FLOAT, clamped.data());
  texture.mipmapTrilinear(GL_REPEAT, GL_CLAMP_TO_EDGE);
  return texture;
}

bool sphereVisible(const glm::dvec4 planes[6], const glm::dvec3& center, double radius) {
  if (radius < 0.0) return true;
  for (int i = 0; i < 6; ++i) {
    if (glm::dot(glm::dvec3(planes[i]), center) + planes[i].w < -radius) return false;
  }
  return true;
}

// The six planes of a view-projection (Gribb-Hartmann), normalised, inside >= 0.
void frustumPlanes(const glm::dmat4& m, glm::dvec4 planes[6]) {
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

}  // namespace

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
  std::optional<SkinMode> skinModeOverride;  // every model's, when set
  QuatInterpolation rotations = QuatInterpolation::Slerp;
  DebugView debugView = DebugView::None;
  gl::Program sky, post;
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
  // The pyramid the terrain's second half was culled with, this frame: without
  // occluders the draws are culled with it (the depth has only come nearer
  // since), which saves a build and a wait.
  bool terrainPyramid = false;
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
  void buildOccluderPyramid(const View& view, const std::vector<DrawItem>& occluders);
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
  void drawTerrain(const glm::dmat4& viewProjection, double fovy, int viewportHeight);
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
  Status loadMaterials();
  Status loadModels();
  void addShapes();
  Status buildVariants();
  Status makeTarget(int width, int height);
  void setUniforms(const gl::Program& program) const;
  Result<DrawLists> collectDraws(const glm::dvec4* planes, bool depthOnly, int skipShape = -1);
  Status collectShapes(const glm::dvec4* planes, bool depthOnly, int skipShape, DrawLists& lists);
  Status collectCharacters(const glm::dvec4* planes, bool depthOnly, DrawLists& lists);
  Status drawItems(const std::vector<DrawItem>& items, const PassInputs& pass, const ItemCommands* commands = nullptr);
  Status submitItems(const std::vector<DrawItem>& items, const PassInputs& pass, const ItemCommands* commands);
  double animationMs = 0.0;  // the last update's
  void drawShape(const ShapeDraw& shape, const gl::Program& program, const PassInputs& pass,
                 const IndirectDraw* indirect);
  glm::mat4 shapeModel(const ShapeDraw& shape) const;
  void drawSky(const glm::dmat4& viewProjection, bool sunDisk = true);
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
  Status makePost();
  bool usesSkinCache(const ModelData& model, const ModelDesc& desc) const;
  std::string describeSkinCache() const;
  void fillFrame(const glm::dvec3& cameraPosition, const glm::mat4& viewProjection);
};

Status SceneRenderer::Impl::init(const SceneRenderOptions& options) {
  shaderDir = options.shaderDir;
  render = scene.render;
  if (options.msaaOverride > 0) render.msaa = options.msaaOverride;
  render.skinning = options.skinningOverride.value_or(render.skinning);
  render.lodPixels = options.lodPixelsOverride.value_or(render.lodPixels);
  render.gpuCulling = options.gpuCullingOverride.value_or(render.gpuCulling);
  cullDepthMargin = options.gpuCullingDepthMargin;
  render.shading = options.shadingOverride.value_or(render.shading);
  if (options.exposureOverride > 0.0f) render.exposure = options.exposureOverride;
  render.toneMap = options.toneMapOverride.value_or(render.toneMap);
  render.output = options.outputOverride.value_or(render.output);
  terrainError = options.terrainErrorOverride > 0.0 ? options.terrainErrorOverride : scene.terrain.errorPixels;
  skinModeOverride = options.skinModeOverride;
  rotations = options.rotations;
  if (options.supersampleOverride > 0) render.supersample = options.supersampleOverride;
  if (options.shadowMapOverride > 0) render.shadowMapSize = options.shadowMapOverride;
  if (options.pcfKernelOverride > 0) {
    render.pcfKernel = options.pcfKernelOverride;
    render.shadowFilter = options.pcfKernelOverride > 1 ? ShadowFilter::Pcf : ShadowFilter::Hard;
  }
  pcfRadius = render.shadowFilter == ShadowFilter::Hard ? 0 : render.pcfKernel / 2;
  // Checked before anything is built: a scene may ask for more samples (up to 16)
  // than this GL offers, and a frame without its target would draw nothing.
  if (const int most = RenderTarget::maxSamples(); render.msaa > most) {
    return makeError(scene.path + ": /render/msaa: " + std::to_string(render.msaa) +
                     " samples asked, this GL offers up to " + std::to_string(most));
  }

  for (int i = 0; i < int(scene.lights.size()); ++i) {
    const LightDesc& l = scene.lights[size_t(i)];
    if (l.type == LightType::Sun && sunLight < 0) sunLight = i;
    // Area lights are drawn as a point at their centre; their soft shadow is the
    // ray tracer's job (PCF only imitates it).
    if (l.type != LightType::Sun && int(pointLights.size()) < kMaxPointLights) pointLights.push_back(i);
  }
  sunShadows = sunLight >= 0 && scene.lights[size_t(sunLight)].shadows;
  pointShadows = !pointLights.empty() && scene.lights[size_t(pointLights[0])].shadows;

  std::vector<std::string> defines;
  if (render.shading == Shading::Classic) defines.push_back("CLASSIC 1");
  if (sunShadows) defines.push_back("SUN_SHADOWS 1");
  sunFarShadows = sunShadows && scene.terrain.enabled;
  if (sunFarShadows) defines.push_back("SUN_FAR_SHADOWS 1");
  if (pointShadows) defines.push_back("POINT_SHADOWS 1");
  if (scene.fog.enabled) defines.push_back("FOG 1");
  if (render.shading == Shading::Pbr) {
    ambient = options.ambientOverride.value_or(ambientOf(scene));
    iblSize = options.iblSizeOverride > 0 ? options.iblSizeOverride : render.iblSize;
    if (ambient == Ambient::Sh) defines.push_back("AMBIENT_SH 1");
    if (ambient == Ambient::Ibl) defines.push_back("AMBIENT_IBL 1");
  }
  debugView = options.debugView;
  if (debugView != DebugView::None) {
    // The value as it is: no exposure, no tone map (post.frag's TONE_MAP 0 clamps).
    defines.push_back("DEBUG_VIEW " + std::to_string(int(debugView)));
    render.exposure = 1.0f;
    render.toneMap = ToneMap::None;
  }
  probeSize = options.reflectionProbeOverride >= 0 ? options.reflectionProbeOverride : render.reflectionProbe;
  if (auto s = makeProbes(); !s) return s;
  if (!probes.empty()) defines.push_back("REFLECTION_PROBES 1");
  directOutput = !options.hdrTarget && needsNoHdrTarget();
  if (directOutput) {
    defines.push_back("DIRECT_OUTPUT 1");
    if (render.output == OutputCurve::Gamma22) defines.push_back("OUTPUT_GAMMA22 1");
  }
  variants = std::make_unique<ShaderVariants>(shaderDir, "scene.vert", "scene.frag", defines);

  if (auto s = makeSky(); !s) return s;
  if (auto s = makePost(); !s) return s;
  emptyVao = gl::VertexArray::create();
  frameUbo = gl::Buffer::create(sizeof(FrameBlock));
  if (auto s = makeEnvironmentLighting(); !s) return s;

  if (auto s = loadTerrain(defines); !s) return s;
  if (auto s = loadMaterials(); !s) return s;
  if (auto s = loadModels(); !s) return s;
  addShapes();
  for (int i = 0; i < int(probes.size()); ++i) shapes[size_t(probes[size_t(i)].shape)].probe = i;
  if (auto s = makeCuller(); !s) return s;

  if (sunShadows) {
    sunShadowSize = render.shadowMapSize;
    sunShadowMap = makeSunShadowMap(sunShadowSize);
    sunShadowFbo = gl::Framebuffer::create();
    sunShadowFbo.attach(GL_DEPTH_ATTACHMENT, sunShadowMap);
    if (auto s = sunShadowFbo.check("shadow-sun"); !s) return s;
  }
  if (sunFarShadows) {
    sunShadowMapFar = makeSunShadowMap(sunShadowSize);
    sunShadowFarFbo = gl::Framebuffer::create();
    sunShadowFarFbo.attach(GL_DEPTH_ATTACHMENT, sunShadowMapFar);
    if (auto s = sunShadowFarFbo.check("shadow-sun-far"); !s) return s;
  }
  if (pointShadows) {
    cubeSize = std::min(render.shadowMapSize, kMaxCubeShadowSize);
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &id);
    glTextureStorage2D(id, 1, GL_DEPTH_COMPONENT32F, cubeSize, cubeSize);
    pointShadowMap = gl::Texture::adopt(id, cubeSize, cubeSize);
    pointShadowMap.parameter(GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    pointShadowMap.parameter(GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    pointShadowMap.parameter(GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    pointShadowMap.parameter(GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    pointShadowFbo = gl::Framebuffer::create();
    // Each face is attached in turn when drawn; all six are alike, so face 0 stands
    // for them here.
    glNamedFramebufferTextureLayer(pointShadowFbo.id(), GL_DEPTH_ATTACHMENT, pointShadowMap.id(), 0, 0);
    if (auto s = pointShadowFbo.check("shadow-point"); !s) return s;
    pointFar = std::max(1.0, scene.camera.farPlane);
  }
  return buildVariants();
}

// The sky pass's program: the gradient, or the SKY_IMAGE variant with its texture,
// uploaded once.
Status SceneRenderer::Impl::makeSky() {
  if (!scene.sky.enabled) return Ok{};
  std::vector<std::string> defines{"HDR_OUTPUT 1"};
  if (!scene.sky.image.empty()) {
    auto image = readLinearImage(scene.sky.image);
    if (!image) return makeError(scene.path + ": /sky/image: " + image.error().message);
    skyImage = uploadSkyImage(*image);
    defines.push_back("SKY_IMAGE 1");
  }
  auto program = gl::Program::build(shaderDir, {{GL_VERTEX_SHADER, "sky.vert"}, {GL_FRAGMENT_SHADER, "sky.frag"}}, defines);
  if (!program) return program.error();
  sky = std::move(program).value();
  return Ok{};
}

// The one post variant these settings need (post.frag says why not uniforms);
// none where the fragment shaders write display values themselves.
Status SceneRenderer::Impl::makePost() {
  if (directOutput) return Ok{};
  std::vector<std::string> defines{"SUPERSAMPLE " + std::to_string(render.supersample),
                                   "TONE_MAP " + std::to_string(int(render.toneMap))};
  if (render.output == OutputCurve::Gamma22) defines.push_back("OUTPUT_GAMMA22 1");
  auto program = gl::Program::build(shaderDir, {{GL_VERTEX_SHADER, "post.vert"}, {GL_FRAGMENT_SHADER, "post.frag"}}, defines);
  if (!program) return program.error();
  post = std::move(program).value();
  return Ok{};
}

// The environment as the path tracer sees it (the sky without its sun disk, or the
// background), drawn into a cube map once: the scene's sky never changes while it
// is loaded. From it the SH irradiance, the BRDF table and, for IBL, the
// prefiltered chain; the cube itself is dropped.
Status SceneRenderer::Impl::makeEnvironmentLighting() {
  if (render.shading == Shading::Classic || ambient == Ambient::Hemisphere) return Ok{};
  const auto start = std::chrono::steady_clock::now();
  GLint callerFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &callerFramebuffer);
  const gl::Texture environment = makeCubeMap(iblSize, 0);
  const gl::Framebuffer fbo = gl::Framebuffer::create();
  // Any 90-degree projection will do: sky.vert takes only directions from it.
  const glm::dmat4 projection = glm::perspective(glm::half_pi<double>(), 1.0, 0.1, 10.0);
  const glm::vec3 background = scene.sky.background;
  glViewport(0, 0, iblSize, iblSize);
  applyPassState(kSkyPass);
  for (int face = 0; face < 6; ++face) {
    glNamedFramebufferTextureLayer(fbo.id(), GL_COLOR_ATTACHMENT0, environment.id(), 0, face);
    if (auto s = fbo.check("ibl-environment"); !s) return s;
    fbo.bind();
    glClearColor(background.r, background.g, background.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    if (scene.sky.enabled) {
      drawSky(projection * glm::lookAt(glm::dvec3(0.0), kCubeFaceDirections[face], kCubeFaceUps[face]), false);
    }
  }
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(callerFramebuffer));
  applyPassState(kCallerState);
  environment.generateMipmaps();
  auto lighting = EnvironmentLighting::create(shaderDir, environment, iblSize, ambient);
  if (!lighting) return makeError(scene.path + ": /render/ambient: " + lighting.error().message);
  environmentLighting = std::move(lighting).value();
  glFinish();
  iblMilliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return Ok{};
}

// One probe per mirror sphere or box (material reflection > 0), up to four. Planes
// get none: a plane mirror needs a planar reflection, which this renderer lacks.
Status SceneRenderer::Impl::makeProbes() {
  if (probeSize <= 0) return Ok{};
  for (int i = 0; i < int(scene.primitives.size()) && int(probes.size()) < kMaxReflectionProbes; ++i) {
    const PrimitiveDesc& p = scene.primitives[size_t(i)];
    if (p.type == PrimitiveType::Plane || scene.materials[size_t(p.material)].reflection <= 0.0f) continue;
    Probe probe;
    probe.shape = i;
    probe.center = p.type == PrimitiveType::Sphere ? p.center : (p.min + p.max) * 0.5;
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &id);
    glTextureStorage2D(id, 1, GL_RGBA16F, probeSize, probeSize);
    probe.cube = gl::Texture::adopt(id, probeSize, probeSize);
    probe.cube.parameter(GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    probe.cube.parameter(GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    probes.push_back(std::move(probe));
  }
  if (probes.empty()) return Ok{};
  glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);  // no seams where faces meet
  probeDepth = gl::Renderbuffer::create(GL_DEPTH_COMPONENT32F, probeSize, probeSize);
  probeFbo = gl::Framebuffer::create();
  probeFbo.attach(GL_DEPTH_ATTACHMENT, probeDepth);
  glNamedFramebufferTextureLayer(probeFbo.id(), GL_COLOR_ATTACHMENT0, probes[0].cube.id(), 0, 0);
  return probeFbo.check("reflection-probe");
}

Status SceneRenderer::Impl::loadTerrain(const std::vector<std::string>& defines) {
  terrain = source->terrain();
  if (!terrain) return Ok{};
  // The scene programs' variant: the terrain is lit and shadowed as they are.
  auto renderer = terrain::TerrainRenderer::create(shaderDir, *terrain, defines);
  if (!renderer) return renderer.error();
  terrainRenderer = std::make_unique<terrain::TerrainRenderer>(std::move(renderer).value());
  return Ok{};
}

// The view camera's LOD (its position, field of view and viewport fix every
// patch's level and morph), culled against `cullViewProjection`; coarsened if it
// would need more height pages than the GPU pool holds.
terrain::LodSelection SceneRenderer::Impl::selectTerrain(const glm::mat4& cullViewProjection, double fovy,
                                                         int viewportHeight) const {
  terrain::LodCamera camera;
  camera.position = eye;
  camera.viewProjection = cullViewProjection;
  camera.zeroToOneDepth = true;  // reverse-Z and the sun's box both clip depth to 0..w
  camera.fovY = fovy;
  camera.viewportHeight = viewportHeight;
  return terrain::selectLodWithin(*terrain, camera, terrainError,
                                  std::size_t(terrainRenderer->pageSlots()));
}

// Every terrain block error the view from `eye` needs, before any of the frame's
// selections: they all see the same errors, so the sun's maps keep the view's
// ranges; and a frame's image depends on its camera alone, not on which frames came
// before (a window and an offscreen run of another length give the same bytes). A
// new view pays about 2 ms a block, once.
void SceneRenderer::Impl::measureTerrain(double fovy, int viewportHeight) {
  terrain::LodCamera camera;
  camera.position = eye;
  camera.fovY = fovy;
  camera.viewportHeight = viewportHeight;
  stats->terrainBlocksPending = int(terrain::measureBlocks(*terrain, camera, terrainError));
}

void SceneRenderer::Impl::drawTerrain(const glm::dmat4& viewProjection, double fovy, int viewportHeight) {
  const auto selection = selectTerrain(glm::mat4(viewProjection), fovy, viewportHeight);
  const auto drawn = terrainRenderer->draw(selection, eye, [this](const gl::Program& p) { setUniforms(p); });
  stats->drawCalls += 1;
  stats->terrainTriangles = int(drawn.trianglesDrawn);
}

// The terrain into the sun's shadow map, with the same patches and morph as the
// view (a coarser mesh would poke through the drawn one and shadow it), culled
// against the light's box stretched toward the sun over the whole field: with depth
// clamping, a mountain in front of the light's near plane still casts, at depth 0.
void SceneRenderer::Impl::drawTerrainShadow(const SunBox& box, double fovy, int viewportHeight) {
  const terrain::HeightRange h = terrain->heightRange();
  const double reach = std::hypot(double(terrain->cellsX()), double(terrain->cellsZ())) * terrain->spacing() +
                       double(h.max - h.min);
  const double r = box.radius;
  const glm::dmat4 cullProjection = glm::orthoRH_ZO(-r, r, -r, r, -reach, 2.0 * r + reach);
  const auto selection = selectTerrain(glm::mat4(cullProjection * box.view), fovy, viewportHeight);
  applyPassState(kTerrainShadowPass);
  terrainRenderer->drawDepth(selection, glm::mat4(box.projection * box.view));
  stats->drawCalls += 1;
}

Status SceneRenderer::Impl::loadMaterials() {
  for (const MaterialDesc& m : scene.materials) {
    auto image = loadMaterialTexture(scene, m);
    if (!image) return image.error();
    materialTextures.push_back(image->empty() ? gl::Texture{} : uploadTexture(*image, true));
  }
  return Ok{};
}

// Whether the frame can skip the HDR target and the post pass (issue 14: a scene
// with no HDR effect pays for none): nothing to tone map or expose, no samples to
// resolve or average, and nothing that reads or blends the linear image (the sky
// and probes are drawn linear for the environment too, blending and transmission
// read what is behind). The fragment shaders then write display values
// (common/output.glsl); the bytes differ from the post pass's by at most one level,
// where it rounded the radiance to half floats first (SceneRenderer.DirectOutput...).
bool SceneRenderer::Impl::needsNoHdrTarget() const {
  if (render.toneMap != ToneMap::None || render.exposure != 1.0f || render.msaa > 1 || render.supersample > 1) return false;
  if (scene.sky.enabled || !probes.empty() || debugView != DebugView::None) return false;
  for (const auto& asset : source->assets()) {
    for (const MaterialData& m : asset->model.materials)
      if (m.alphaMode == AlphaMode::Blend || m.layers.transmissive()) return false;
  }
  return true;
}

// Whether an instance deforms in the skin cache. render.skinning auto sends it
// there where each vertex would otherwise be deformed again at a price in every
// pass that draws it (measured: bench/morph_cost, bench/skinning_cost): morph
// targets (8 of them cost 1.5x the frame in the vertex shaders, 1.1-1.2x cached),
// dual quaternions, or more than the view and one sun map drawing it (a point
// light's six cube faces, the probes). Plain LBS under a sun stays in the vertex
// shaders, cheaper there than a dispatch that writes 48 bytes a vertex.
bool SceneRenderer::Impl::usesSkinCache(const ModelData& model, const ModelDesc& desc) const {
  if (render.skinning == Skinning::Vertex) return false;
  bool skins = false, morphs = false;
  for (const NodeData& node : model.nodes) {
    if (node.mesh < 0) continue;
    for (const PrimitiveData& prim : model.meshes[size_t(node.mesh)].primitives) {
      skins = skins || (node.skin >= 0 && prim.influences > 0 && !desc.unskinned);
      morphs = morphs || prim.morphTargets > 0;
    }
  }
  if (render.skinning == Skinning::Compute) return skins || morphs;
  const bool manyPasses = pointShadows || !probes.empty();
  return morphs || (skins && (desc.dualQuat || manyPasses));
}

// One upload per model file, one CharacterInstance per scene instance.
Status SceneRenderer::Impl::loadModels() {
  std::vector<std::shared_ptr<const CharacterAsset>> uploaded;
  for (const auto& asset : source->assets()) {
    auto created = CharacterAsset::create(asset, render.lodPixels > 0.0);
    if (!created) return makeError(scene.path + ": " + asset->model.path + ": " + created.error().message);
    uploaded.push_back(std::move(created).value());
  }
  for (const ModelInstance& instance : source->instances()) {
    CharacterDraw draw;
    draw.instance = std::make_unique<CharacterInstance>(uploaded[size_t(instance.asset)]);
    draw.instance->setPose(instance.pose);
    draw.desc = instance.desc;
    if (skinModeOverride) {
      draw.desc.dualQuat = *skinModeOverride == SkinMode::DualQuat;
      draw.desc.unskinned = *skinModeOverride == SkinMode::None;
    }
    if (usesSkinCache(draw.instance->asset().model, draw.desc)) {
      if (!skinPrograms) skinPrograms = std::make_unique<SkinPrograms>(shaderDir);
      draw.instance->useSkinCache(skinPrograms.get());
    }
    draw.world = instance.world;
    draw.localCenter = instance.boundsCenter;
    draw.localRadius = instance.boundsRadius;
    characters.push_back(std::move(draw));
  }
  return Ok{};
}

void SceneRenderer::Impl::addShapes() {
  for (const PrimitiveDesc& p : scene.primitives) {
    ShapeDraw draw;
    draw.material = p.material;
    draw.world = primitiveTransform(p, scene.camera.farPlane);
    std::unique_ptr<GpuMesh>& mesh =
        p.type == PrimitiveType::Sphere ? sphere : p.type == PrimitiveType::Box ? cube : quad;
    if (!mesh) mesh = std::make_unique<GpuMesh>(shapeForPrimitive(p));
    draw.mesh = mesh.get();
    if (p.type == PrimitiveType::Sphere) {
      draw.center = p.center;
      draw.radius = p.radius;
    } else if (p.type == PrimitiveType::Box) {
      draw.center = (p.min + p.max) * 0.5;
      draw.radius = 0.5 * glm::length(p.max - p.min);
    } else {
      // The quad's uv spans 2 units; one texture tile per `1 / texture_scale` metres.
      const double extent = planeExtent(p, scene.camera.farPlane);
      draw.uvScale = glm::vec2(float(extent) * scene.materials[size_t(p.material)].textureScale);
      draw.twoSided = true;
    }
    shapes.push_back(draw);
  }
}

Status SceneRenderer::Impl::buildVariants() {
  // Everything the scene will draw, built now, so the first frame costs no
  // compile and --describe can list exactly what exists.
  std::vector<ShaderVariant> needed;
  for (const ShapeDraw& s : shapes) needed.push_back({0, SkinMode::Linear, materialTextures[size_t(s.material)].id() != 0, false});
  for (const CharacterDraw& c : characters) {
    const ModelData& model = c.instance->asset().model;
    const SkinMode mode = skinModeOf(c.desc);
    const bool cached = c.instance->skinCache() != nullptr;
    // Deforms the first pose, which builds the skin cache's compute programs too.
    if (auto s = c.instance->prepare(mode); !s) return s;
    for (const NodeData& node : model.nodes) {
      if (node.mesh < 0) continue;
      for (const PrimitiveData& prim : model.meshes[size_t(node.mesh)].primitives) {
        needed.push_back(primitiveVariant(model, node, prim, mode, false, cached));
        const bool blend = prim.material >= 0 && model.materials[size_t(prim.material)].alphaMode == AlphaMode::Blend;
        if ((sunShadows || pointShadows) && !blend) needed.push_back(primitiveVariant(model, node, prim, mode, true, cached));
        blendPass = blendPass || blend;
        transmissionPass = transmissionPass || (prim.material >= 0 && model.materials[size_t(prim.material)].layers.transmissive());
      }
    }
  }
  if ((sunShadows || pointShadows) && !shapes.empty()) needed.push_back({0, SkinMode::Linear, false, true});
  for (const ShaderVariant& v : needed) {
    auto program = variants->get(v);
    if (!program) return program.error();
  }
  return Ok{};
}

Status SceneRenderer::Impl::makeTarget(int width, int height) {
  const int w = width * render.supersample, h = height * render.supersample;
  if (w == targetWidth && h == targetHeight && drawFbo) return Ok{};
  targetWidth = w;
  targetHeight = h;
  hdr = gl::Texture::create2D(directOutput ? GL_RGBA8 : GL_RGBA16F, w, h, 1);
  hdr.parameter(GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  hdr.parameter(GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  const int samples = render.msaa > 1 ? render.msaa : 0;
  depth = gl::Renderbuffer::create(GL_DEPTH_COMPONENT32F, w, h, samples);
  drawFbo = gl::Framebuffer::create();
  if (samples > 0) {
    msaaColor = gl::Renderbuffer::create(GL_RGBA16F, w, h, samples);
    drawFbo.attach(GL_COLOR_ATTACHMENT0, msaaColor);
    resolveFbo = gl::Framebuffer::create();
    resolveFbo.attach(GL_COLOR_ATTACHMENT0, hdr);
  } else {
    drawFbo.attach(GL_COLOR_ATTACHMENT0, hdr);
  }
  drawFbo.attach(GL_DEPTH_ATTACHMENT, depth);
  if (auto s = drawFbo.check(directOutput ? "scene-display" : "scene-hdr"); !s) return s;
  if (transmissionPass) {
    const int levels = 1 + int(std::floor(std::log2(double(std::max(w, h)))));
    transmissionSource = gl::Texture::create2D(GL_RGBA16F, w, h, levels);
    transmissionSource.parameter(GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    transmissionSource.parameter(GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    transmissionSource.parameter(GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    transmissionSource.parameter(GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    transmissionFbo = gl::Framebuffer::create();
    transmissionFbo.attach(GL_COLOR_ATTACHMENT0, transmissionSource);
    if (auto s = transmissionFbo.check("transmission-source"); !s) return s;
  }
  return samples > 0 ? resolveFbo.check("scene-hdr-resolve") : Status(Ok{});
}

void SceneRenderer::Impl::setUniforms(const gl::Program& program) const {
  if (sunShadows) {
    program.set("u_sunTexelWorld", float(sunTexelWorld));
    sunShadowMap.bind(gl::binding::kSunShadow);
    if (sunFarShadows) sunShadowMapFar.bind(gl::binding::kSunShadowFar);
  }
  if (pointShadows) {
    program.set("u_pointNear", float(pointNear));
    pointShadowMap.bind(gl::binding::kPointShadow);
  }
}

void SceneRenderer::Impl::fillFrame(const glm::dvec3& cameraPosition, const glm::mat4& viewProjection) {
  frame.viewProjection = viewProjection;
  frame.sunDirection = glm::vec4(0.0f);
  if (sunLight >= 0) {
    const LightDesc& sun = scene.lights[size_t(sunLight)];
    frame.sunDirection = glm::vec4(glm::vec3(sun.direction), 1.0f);
    frame.sunColor = glm::vec4(sun.color * sun.intensity, 0.0f);
  }
  frame.counts = glm::ivec4(int(pointLights.size()), 0, 0, 0);
  for (size_t i = 0; i < pointLights.size(); ++i) {
    const LightDesc& l = scene.lights[size_t(pointLights[i])];
    frame.pointPosition[i] = glm::vec4(glm::vec3(l.position - cameraPosition), l.falloff ? 1.0f : 0.0f);
    frame.pointColor[i] = glm::vec4(l.color * l.intensity, l.shadows ? 1.0f : 0.0f);
  }
  // Ambient from the sky: the zenith and ground colours, dimmed.
  frame.ambientSky = glm::vec4(ambientSkyColor(scene), scene.ambient);
  frame.ambientGround = glm::vec4(ambientGroundColor(scene), 0.0f);
  frame.fog = scene.fog.enabled ? glm::vec4(scene.fog.color, scene.fog.density) : glm::vec4(0.0f);
  frame.shadowParams = glm::vec4(sunShadowSize ? 1.0f / float(sunShadowSize) : 0.0f, float(pcfRadius),
                                 float(pointFar), cubeSize ? 2.0f / float(cubeSize) : 0.0f);
  if (environmentLighting) {
    for (int i = 0; i < 9; ++i) frame.shIrradiance[i] = glm::vec4(environmentLighting->sh().coefficients[size_t(i)], 0.0f);
    frame.iblParams = glm::vec4(float(environmentLighting->maxLevel()), 0.0f, 0.0f, 0.0f);
    environmentLighting->bind();
  }
  frameUbo.upload(0, sizeof(FrameBlock), &frame);
  glBindBufferBase(GL_UNIFORM_BUFFER, gl::binding::kFrameBlock, frameUbo.id());
}

// The scene's shapes for one view: culled, each with its program (shadow passes
// draw the depth-only one), keyed by program, material and distance.
Status SceneRenderer::Impl::collectShapes(const glm::dvec4* planes, bool depthOnly, int skipShape, DrawLists& lists) {
  for (int index = 0; index < int(shapes.size()); ++index) {
    const ShapeDraw& s = shapes[size_t(index)];
    if (index == skipShape) continue;
    const glm::dvec3 center = s.center - eye;
    if (planes && !sphereVisible(planes, center, s.radius)) {
      ++stats->objectsCulled;
      continue;
    }
    ++stats->objectsDrawn;
    const bool textured = !depthOnly && materialTextures[size_t(s.material)].id() != 0;
    auto program = variants->get({0, SkinMode::Linear, textured, depthOnly});
    if (!program) return program.error();
    const GLuint id = (*program)->id();
    const double distance = s.radius < 0.0 ? 0.0 : glm::length(center);
    lists.opaque.push_back({DrawItem::Source::Shape, index, -1, -1, id, opaqueKey(id, std::uint32_t(s.material), distance)});
  }
  return Ok{};
}

// Every primitive of every visible character: opaque and MASK ones keyed like
// shapes (materials after the scene's own), BLEND ones back to front by the centre
// of their bounds (whole primitives, so intersecting panes can still be out of
// order). Shadow passes take no BLEND primitive: a tinted pane in a depth map
// would be an opaque sheet.
Status SceneRenderer::Impl::collectCharacters(const glm::dvec4* planes, bool depthOnly, DrawLists& lists) {
  for (int index = 0; index < int(characters.size()); ++index) {
    const CharacterDraw& c = characters[size_t(index)];
    const glm::dvec3 center = glm::dvec3(c.world * glm::dvec4(c.localCenter, 1.0)) - eye;
    if (planes && !sphereVisible(planes, center, c.localRadius)) {
      ++stats->objectsCulled;
      continue;
    }
    ++stats->objectsDrawn;
    const ModelData& model = c.instance->asset().model;
    const SkinMode mode = skinModeOf(c.desc);
    const bool cached = c.instance->skinCache() != nullptr;
    const double distance = glm::length(center);
    for (int n = 0; n < int(model.nodes.size()); ++n) {
      const NodeData& node = model.nodes[size_t(n)];
      if (node.mesh < 0) continue;
      const auto& prims = model.meshes[size_t(node.mesh)].primitives;
      for (int p = 0; p < int(prims.size()); ++p) {
        const PrimitiveData& prim = prims[size_t(p)];
        const bool blend = prim.material >= 0 && model.materials[size_t(prim.material)].alphaMode == AlphaMode::Blend;
        if (blend && depthOnly) continue;
        auto program = variants->get(primitiveVariant(model, node, prim, mode, depthOnly, cached));
        if (!program) return program.error();
        const GLuint id = (*program)->id();
        const bool transmissive =
            !depthOnly && prim.material >= 0 && model.materials[size_t(prim.material)].layers.transmissive();
        lists.refracts = lists.refracts || transmissive;
        if (!blend) {
          const std::uint32_t material = std::uint32_t(scene.materials.size()) + std::uint32_t(std::max(prim.material, 0));
          (transmissive ? lists.transmissive : lists.opaque)
              .push_back({DrawItem::Source::Character, index, n, p, id, opaqueKey(id, material, distance)});
        }
      }
    }
    if (depthOnly) continue;
    for (const BlendPrimitive& b : c.instance->blendPrimitives()) {
      auto program = variants->get(primitiveVariant(model, model.nodes[size_t(b.node)],
                                                    model.meshes[size_t(model.nodes[size_t(b.node)].mesh)].primitives[size_t(b.primitive)],
                                                    mode, false, cached));
      if (!program) return program.error();
      lists.blend.push_back({DrawItem::Source::Character, index, b.node, b.primitive, (*program)->id(), blendKey(b.distance)});
    }
  }
  return Ok{};
}

Result<DrawLists> SceneRenderer::Impl::collectDraws(const glm::dvec4* planes, bool depthOnly, int skipShape) {
  const auto start = std::chrono::steady_clock::now();
  DrawLists lists;
  if (auto s = collectShapes(planes, depthOnly, skipShape, lists); !s) return s.error();
  if (auto s = collectCharacters(planes, depthOnly, lists); !s) return s.error();
  sortDrawItems(lists.opaque);
  sortDrawItems(lists.transmissive);
  sortDrawItems(lists.blend);
  stats->cullMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return lists;
}

// A shape's u_model, camera-relative: the offset is taken in double, then the
// matrix goes to float. GPU culling transforms its clusters by the same matrix.
glm::mat4 SceneRenderer::Impl::shapeModel(const ShapeDraw& s) const {
  glm::dmat4 relative = s.world;
  relative[3] -= glm::dvec4(eye, 0.0);
  return glm::mat4(relative);
}

void SceneRenderer::Impl::drawShape(const ShapeDraw& s, const gl::Program& p, const PassInputs& pass,
                                    const IndirectDraw* indirect) {
  const MaterialDesc& m = scene.materials[size_t(s.material)];
  const glm::mat4 model = shapeModel(s);
  p.set("u_model", model);
  p.set("u_normalMatrix", glm::mat3(glm::transpose(glm::inverse(glm::mat3(model)))));
  p.set("u_uvScale", s.uvScale * (s.mesh == quad.get() ? 1.0f : m.textureScale));
  if (pass.depthOnly) {
    p.set("u_lightViewProjection", pass.lightViewProjection);
  } else {
    p.set("u_baseColorFactor", glm::vec4(m.color, 1.0f));
    p.set("u_metallic", m.metallic);
    p.set("u_roughness", m.roughness);
    p.set("u_ambient", m.ambient);
    p.set("u_diffuse", m.diffuse);
    p.set("u_specular", m.specular);
    p.set("u_shininess", m.shininess);
    p.set("u_reflection", m.reflection);
    p.set("u_emissive", m.emission);
    if (materialTextures[size_t(s.material)].id() != 0) materialTextures[size_t(s.material)].bind(gl::binding::kBaseColor);
    if (!probes.empty()) {
      const bool probed = pass.useProbes && s.probe >= 0;
      p.set("u_hasProbe", probed ? 1 : 0);
      if (probed) probes[size_t(s.probe)].cube.bind(gl::binding::kReflectionProbe);
    }
  }
  // Two-sided: no culling for this draw, and the pass's setting put back (the
  // point light's cube pass culls nothing: turning culling on after the ground
  // would cull every caster drawn after it, as the sort order falls).
  const bool twoSided = s.twoSided && glIsEnabled(GL_CULL_FACE);
  if (twoSided) glDisable(GL_CULL_FACE);
  if (indirect) {
    s.mesh->drawIndirect(indirect->offset, indirect->count);
  } else {
    s.mesh->draw();
  }
  if (twoSided) glEnable(GL_CULL_FACE);
}

// The items in order, in the pass state the caller set. A program's pass-wide
// uniforms (shadow parameters) are set when the pass first binds it, and each
// change of program is counted: sorting keeps the count near the number of
// programs the view needs.
Status SceneRenderer::Impl::drawItems(const std::vector<DrawItem>& items, const PassInputs& pass,
                                      const ItemCommands* commands) {
  const auto start = std::chrono::steady_clock::now();
  const Status status = submitItems(items, pass, commands);
  stats->submitMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return status;
}

Status SceneRenderer::Impl::submitItems(const std::vector<DrawItem>& items, const PassInputs& pass,
                                        const ItemCommands* commands) {
  std::vector<std::uint32_t> programs;
  for (const DrawItem& item : items) programs.push_back(item.program);
  std::sort(programs.begin(), programs.end());
  stats->programsNeeded += int(std::unique(programs.begin(), programs.end()) - programs.begin());
  GLuint bound = 0;
  auto set = [&](const gl::Program& p) {
    if (p.id() == bound) return;
    bound = p.id();
    ++stats->programChanges;
    setUniforms(p);
    if (pass.depthOnly) p.set("u_lightViewProjection", pass.lightViewProjection);
  };
  for (std::size_t k = 0; k < items.size(); ++k) {
    const DrawItem& item = items[k];
    const std::span<const IndirectDraw> indirect =
        commands ? std::span<const IndirectDraw>((*commands)[k]) : std::span<const IndirectDraw>();
    ++stats->drawCalls;
    if (item.source == DrawItem::Source::Shape) {
      const ShapeDraw& shape = shapes[size_t(item.object)];
      const bool textured = !pass.depthOnly && materialTextures[size_t(shape.material)].id() != 0;
      auto program = variants->get({0, SkinMode::Linear, textured, pass.depthOnly});
      if (!program) return program.error();
      (*program)->use();
      set(**program);
      drawShape(shape, **program, pass, indirect.empty() ? nullptr : &indirect[0]);
      continue;
    }
    CharacterDraw& c = characters[size_t(item.object)];
    if (auto s = c.instance->drawPrimitive(*variants, pass.viewProjection, skinModeOf(c.desc), set, pass.depthOnly,
                                           item.node, item.primitive, indirect);
        !s) {
      return s;
    }
  }
  return Ok{};
}

// The bounding sphere of the view frustum's slice [nearPlane, farPlane],
// camera-relative, its radius rounded up to whole metres: a stable size, so that
// texels do not change every frame.
SceneRenderer::Impl::ShadowSphere SceneRenderer::Impl::frustumSlice(const glm::dmat4& view, double fovy, double aspect,
                                                                    double nearPlane, double farPlane) {
  const glm::dmat4 invView = glm::inverse(view);
  const double ty = std::tan(fovy * 0.5), tx = ty * aspect;
  glm::dvec3 corners[8];
  int k = 0;
  for (double d : {nearPlane, farPlane})
    for (double sy : {-1.0, 1.0})
      for (double sx : {-1.0, 1.0}) corners[k++] = glm::dvec3(invView * glm::dvec4(sx * tx * d, sy * ty * d, -d, 1.0));
  ShadowSphere slice;
  for (const auto& c : corners) slice.center += c / 8.0;
  for (const auto& c : corners) slice.radius = std::max(slice.radius, glm::length(c - slice.center));
  slice.radius = std::ceil(slice.radius);
  return slice;
}

// The sun's orthographic box around `around` (relative to `eye`), texel-snapped.
SceneRenderer::Impl::SunBox SceneRenderer::Impl::fitSunBox(const ShadowSphere& around) const {
  const double radius = around.radius;
  glm::dvec3 center = around.center;
  const glm::dvec3 l = scene.lights[size_t(sunLight)].direction;
  const glm::dvec3 up = std::abs(l.y) > 0.99 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 lx = glm::normalize(glm::cross(up, l)), ly = glm::cross(l, lx);
  // Snap the centre to whole texels in world space: the map then slides in texel
  // steps as the camera moves, and shadow edges do not shimmer.
  SunBox box;
  box.radius = radius;
  box.texelWorld = 2.0 * radius / double(sunShadowSize);
  const double texel = box.texelWorld;
  const glm::dvec3 world = center + eye;
  const double u = glm::dot(world, lx), v = glm::dot(world, ly);
  center += lx * (std::floor(u / texel) * texel - u) + ly * (std::floor(v / texel) * texel - v);

  const double casterMargin = 200.0;  // casters behind the view still throw shadows into it
  box.view = glm::lookAt(center + l * (radius + casterMargin), center, ly);
  box.projection = glm::orthoRH_ZO(-radius, radius, -radius, radius, 0.0, 2.0 * radius + casterMargin);
  const glm::dmat4 bias = glm::translate(glm::dmat4(1.0), glm::dvec3(0.5, 0.5, 0.0)) *
                          glm::scale(glm::dmat4(1.0), glm::dvec3(0.5, 0.5, 1.0));
  box.shadowMatrix = glm::mat4(bias * box.projection * box.view);
  return box;
}

// The sun's maps around two spheres relative to `eye` (characters posed for it):
// the near one of everything, the far one of the terrain alone. The frame block's
// shadow matrices then belong to this eye.
Status SceneRenderer::Impl::renderSunShadow(const ShadowSphere& nearSphere, const ShadowSphere& farSphere,
                                            double fovy, int viewportHeight) {
  const SunBox box = fitSunBox(nearSphere);
  sunTexelWorld = box.texelWorld;
  frame.sunShadowMatrix = box.shadowMatrix;
  const glm::mat4 lightViewProjection(box.projection * box.view);

  sunShadowFbo.bind();
  glViewport(0, 0, sunShadowSize, sunShadowSize);
  applyPassState(kShadowPass);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  // Every caster: the sun's box is fitted to what the view sees, not culled to it.
  auto casters = collectDraws(nullptr, true);
  if (!casters) return casters.error();
  if (auto s = drawItems(casters->opaque, {true, lightViewProjection, lightViewProjection}); !s) return s;
  if (terrain) drawTerrainShadow(box, fovy, viewportHeight);

  if (sunFarShadows) {
    // The far map: the terrain alone (mountains over valleys), out to a few km.
    const SunBox far = fitSunBox(farSphere);
    frame.sunShadowMatrixFar = far.shadowMatrix;
    frame.sunFarParams = glm::vec4(1.0f / float(sunShadowSize), float(far.texelWorld), 0.0f, 0.0f);
    sunShadowFarFbo.bind();
    glClear(GL_DEPTH_BUFFER_BIT);
    drawTerrainShadow(far, fovy, viewportHeight);
  }
  return Ok{};
}

Status SceneRenderer::Impl::renderPointShadow(const glm::dvec3& cameraPosition) {
  const glm::dvec3 light = scene.lights[size_t(pointLights[0])].position - cameraPosition;
  const glm::dmat4 proj = glm::perspectiveRH_ZO(glm::half_pi<double>(), 1.0, pointNear, pointFar);
  glViewport(0, 0, cubeSize, cubeSize);
  applyPassState(kCubeShadowPass);
  glClearDepth(1.0);
  // One list for the six faces: nothing is culled to a face.
  auto casters = collectDraws(nullptr, true);
  if (!casters) return casters.error();
  for (int face = 0; face < 6; ++face) {
    glNamedFramebufferTextureLayer(pointShadowFbo.id(), GL_DEPTH_ATTACHMENT, pointShadowMap.id(), 0, face);
    pointShadowFbo.bind();
    glClear(GL_DEPTH_BUFFER_BIT);
    const glm::mat4 faceViewProjection(proj * glm::lookAt(light, light + kCubeFaceDirections[face], kCubeFaceUps[face]));
    if (auto s = drawItems(casters->opaque, {true, faceViewProjection, faceViewProjection}); !s) return s;
  }
  return Ok{};
}

void SceneRenderer::Impl::drawSky(const glm::dmat4& viewProjection, bool sunDisk) {
  sky.use();
  if (skyImage) {
    const float radians = glm::radians(scene.sky.rotationDegrees);
    sky.set("u_skyIntensity", scene.sky.intensity);
    sky.set("u_skyRotation", glm::vec2(std::cos(radians), std::sin(radians)));
    skyImage.bind(gl::binding::kSkyImage);
  } else {
    Lighting lighting;
    lighting.sunDirection = sunLight >= 0 ? glm::vec3(scene.lights[size_t(sunLight)].direction) : glm::vec3(0, -1, 0);
    lighting.sunDisk = sunDisk && sunLight >= 0 && scene.sky.sunDisk;
    lighting.skyZenith = scene.sky.zenith;
    lighting.skyHorizon = scene.sky.horizon;
    lighting.skyGround = scene.sky.ground;
    setSkyUniforms(sky, lighting);
  }
  sky.set("u_inverseViewProjection", glm::mat4(glm::inverse(viewProjection)));
  emptyVao.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  ++stats->drawCalls;
}

// Everything a colour pass shows, into the bound HDR framebuffer (cleared): the
// sky, the terrain, the opaque draws of the view, the transmissive ones over a copy
// of those, then its blended ones.
Status SceneRenderer::Impl::drawWorld(const View& view, int skipShape, bool useProbes) {
  if (scene.sky.enabled) {
    applyPassState(kSkyPass);
    drawSky(view.viewProjection);
  }
  applyPassState(opaquePassFor(view.mirrored));
  if (terrain && terrainCuller && view.main) {
    drawTerrainCulled(view);
  } else if (terrain) {
    drawTerrain(view.viewProjection, view.fovy, view.height);
  }
  auto lists = collectDraws(view.planes, false, skipShape);
  if (!lists) return lists.error();
  if (culler && view.main) return drawCulled(view, *lists, useProbes);
  const PassInputs pass{false, glm::mat4(1.0f), glm::mat4(view.viewProjection), useProbes};
  if (auto s = drawItems(lists->opaque, pass); !s) return s;
  if (lists->refracts) {
    if (view.main) copyTransmissionSource();
    transmissionSource.bind(gl::binding::kTransmissionSource);
    if (auto s = drawItems(lists->transmissive, pass); !s) return s;
  }
  if (lists->blend.empty()) return Ok{};
  applyPassState(blendPassFor(view.mirrored));
  return drawItems(lists->blend, pass);
}

// GPU culling's programs and cluster table: every shape mesh's and every model
// primitive's clusters (made when they were uploaded), once per mesh.
Status SceneRenderer::Impl::makeCuller() {
  if (!render.gpuCulling) return Ok{};
  auto made = GpuCuller::create(shaderDir);
  if (!made) return makeError(scene.path + ": /render/gpu_culling: " + made.error().message);
  culler = std::make_unique<GpuCuller>(std::move(made).value());
  if (terrain) {
    auto forTerrain = GpuCuller::create(shaderDir);
    if (!forTerrain) return makeError(scene.path + ": /render/gpu_culling: " + forTerrain.error().message);
    terrainCuller = std::make_unique<GpuCuller>(std::move(forTerrain).value());
  }
  auto pyramid = HiZPyramid::create(shaderDir);
  if (!pyramid) return makeError(scene.path + ": /render/gpu_culling: " + pyramid.error().message);
  hiz = std::make_unique<HiZPyramid>(std::move(pyramid).value());
  for (const GpuMesh* mesh : {sphere.get(), cube.get(), quad.get()})
    if (mesh) shapeClusterBase[mesh] = culler->addClusters(mesh->clusters());
  for (const CharacterDraw& c : characters)
    for (const auto& mesh : c.instance->asset().gpu.meshes())
      for (const GpuPrimitive& p : mesh)
        if (!p.clusters.empty() && !primitiveClusterBase.count(&p)) primitiveClusterBase[&p] = culler->addClusters(p.clusters);
  return Ok{};
}

// A shape's job: its own matrix and clusters, its bounding sphere (none for a plane).
std::vector<IndirectDraw> SceneRenderer::Impl::queueShapeJob(const ShapeDraw& s) {
  cull::Job job;
  job.model = shapeModel(s);
  job.sphere = s.radius < 0.0 ? glm::vec4(0.0f, 0.0f, 0.0f, -1.0f) : glm::vec4(glm::vec3(s.center - eye), float(s.radius));
  const cull::ClusterRange range = s.mesh->clusterRange();
  job.firstCluster = shapeClusterBase.at(s.mesh) + range.first;
  job.clusterCount = range.count;
  return {culler->commandsOf(culler->addJob(job))};
}

// A character primitive's jobs, one per mesh instance, in the order drawPrimitive
// draws them: the clusters of the level of detail it will draw, the character's
// bounding sphere (of every pose: the bounds collectCharacters culls by). A
// skinned or morphed primitive's vertices move away from the rest positions its
// clusters were bounded by, so only its sphere is tested (cull::kInstanceOnly).
std::vector<IndirectDraw> SceneRenderer::Impl::queueCharacterJobs(const DrawItem& item) {
  const CharacterDraw& c = characters[size_t(item.object)];
  const ModelData& model = c.instance->asset().model;
  const NodeData& node = model.nodes[size_t(item.node)];
  const GpuPrimitive& prim = c.instance->asset().gpu.meshes()[size_t(node.mesh)][size_t(item.primitive)];
  const PrimitiveData& data = model.meshes[size_t(node.mesh)].primitives[size_t(item.primitive)];
  if (!hasClusters(prim, data.mode)) return {};
  const SkinMode mode = skinModeOf(c.desc);
  const int level = levelIndexWithin(prim, c.instance->lodBudget());
  const cull::ClusterRange range = level < 0 ? prim.fullClusters : prim.levels[size_t(level)].clusters;
  cull::Job job;
  const glm::dvec3 center = glm::dvec3(c.world * glm::dvec4(c.localCenter, 1.0)) - eye;
  job.sphere = glm::vec4(glm::vec3(center), float(c.localRadius));
  job.firstCluster = primitiveClusterBase.at(&prim) + range.first;
  job.clusterCount = range.count;
  job.flags = skinnedBy(node, data.influences, mode) || data.morphTargets > 0 ? cull::kInstanceOnly : 0u;
  std::vector<IndirectDraw> out;
  for (const glm::mat4& m : c.instance->instanceModels(mode, item.node, data.influences)) {
    job.model = m;
    out.push_back(culler->commandsOf(culler->addJob(job)));
  }
  return out;
}

ItemCommands SceneRenderer::Impl::queueJobs(const std::vector<DrawItem>& items) {
  ItemCommands out;
  out.reserve(items.size());
  for (const DrawItem& item : items) {
    out.push_back(item.source == DrawItem::Source::Shape ? queueShapeJob(shapes[size_t(item.object)])
                                                         : queueCharacterJobs(item));
  }
  return out;
}

// Culls jobs [firstJob, endJob) for the main view: against a pyramid of the depth
// drawn into the bound framebuffer so far, or the frustum alone. The depth only
// ever comes nearer during the view's pass (GL_GREATER, no clears), so what it
// hides now stays hidden for the rest of the pass.
void SceneRenderer::Impl::cullPhase(GpuCuller& with, std::size_t firstJob, std::size_t endJob, const View& view,
                                    bool occlusion) {
  if (endJob <= firstJob) return;
  // The pyramid needs the depth drawn so far, which llvmpipe rasterises only when
  // flushed: waited for here, so that the time below is the culling's own.
  if (occlusion) glFinish();
  const auto start = std::chrono::steady_clock::now();
  if (occlusion) {
    GLint framebuffer = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    hiz->build(GLuint(framebuffer), targetWidth, targetHeight);
  }
  with.cull(firstJob, endJob, glm::mat4(view.viewProjection), occlusion ? hiz.get() : nullptr, cullDepthMargin);
  ++stats->cullDispatches;
  stats->gpuCullMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Whether an opaque item can stand in the occluder prepass: a shape, or a model
// primitive that neither deforms (the prepass would need its skinning) nor cuts
// holes (MASK); either way one drawn in this very pass, so the depth it leaves in
// the prepass is depth the pass's own depth buffer will hold.
bool SceneRenderer::Impl::isOccluder(const DrawItem& item) const {
  if (item.source == DrawItem::Source::Shape) return true;
  const CharacterDraw& c = characters[size_t(item.object)];
  const ModelData& model = c.instance->asset().model;
  const NodeData& node = model.nodes[size_t(item.node)];
  const PrimitiveData& data = model.meshes[size_t(node.mesh)].primitives[size_t(item.primitive)];
  const MaterialData* material = data.material >= 0 ? &model.materials[size_t(data.material)] : nullptr;
  return !skinnedBy(node, data.influences, skinModeOf(c.desc)) && data.morphTargets == 0 &&
         !(material && material->alphaMode != AlphaMode::Opaque);
}

// The pyramid the main view's draws are culled against: the depth drawn so far
// (the terrain's), and the occluders' depth drawn over a copy of it, depth only
// (the occluder prepass). Why that is safe though the occluders come later in the
// pass: an item whose every pixel has, in the end, a strictly nearer depth is
// never the nearest fragment anywhere, and with GL_GREATER the image and the
// depth are the first nearest fragment's; removing a fragment that is not the
// nearest changes neither. Every occluder is an opaque draw of this pass, and the
// pass's final depth is at least the prepass's (up to float rounding between two
// programs' vertex shaders, far inside cull::kDepthMargin). Without occluders the
// terrain's pyramid, made for its second half, serves as it is.
void SceneRenderer::Impl::buildOccluderPyramid(const View& view, const std::vector<DrawItem>& occluders) {
  GLint framebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
  hiz->copyDepth(GLuint(framebuffer), targetWidth, targetHeight);
  if (!occluders.empty()) {
    glBindFramebuffer(GL_FRAMEBUFFER, hiz->depthFramebuffer());
    const glm::mat4 viewProjection(view.viewProjection);
    (void)drawItems(occluders, {true, viewProjection, viewProjection, false});
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(framebuffer));
  }
  hiz->reduce();
}

// The main view's draws with GPU culling, in the order drawWorld draws them, every
// one culled in one dispatch against the occluder pyramid (above). A window's
// frames and a single offscreen frame cull alike: the pyramid is this frame's own,
// never the last frame's. MSAA, or no terrain and no occluder: the frustum only
// (MSAA's pyramid would need every sample's depth).
Status SceneRenderer::Impl::drawCulled(const View& view, const DrawLists& lists, bool useProbes) {
  culler->clearJobs();
  const ItemCommands opaqueCommands = queueJobs(lists.opaque);
  const ItemCommands transmissiveCommands = queueJobs(lists.transmissive);
  const ItemCommands blendCommands = queueJobs(lists.blend);
  culler->upload();
  std::vector<DrawItem> occluders;
  std::copy_if(lists.opaque.begin(), lists.opaque.end(), std::back_inserter(occluders),
               [this](const DrawItem& item) { return isOccluder(item); });
  const bool occlusion = render.msaa <= 1 && (terrain || !occluders.empty());
  // The occluders' depth waits for what is drawn before it: timed from there.
  if (occlusion && !(terrainPyramid && occluders.empty())) glFinish();
  const auto start = std::chrono::steady_clock::now();
  if (occlusion && !(terrainPyramid && occluders.empty())) {
    buildOccluderPyramid(view, occluders);
    applyPassState(opaquePassFor(view.mirrored));
  }
  terrainPyramid = false;
  culler->cull(0, culler->jobCount(), glm::mat4(view.viewProjection), occlusion ? hiz.get() : nullptr, cullDepthMargin);
  ++stats->cullDispatches;
  stats->gpuCullMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const PassInputs pass{false, glm::mat4(1.0f), glm::mat4(view.viewProjection), useProbes};
  Status status = drawItems(lists.opaque, pass, &opaqueCommands);
  if (status && lists.refracts) {
    copyTransmissionSource();
    transmissionSource.bind(gl::binding::kTransmissionSource);
    status = drawItems(lists.transmissive, pass, &transmissiveCommands);
  }
  if (status && !lists.blend.empty()) {
    applyPassState(blendPassFor(view.mirrored));
    status = drawItems(lists.blend, pass, &blendCommands);
  }
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  return status;
}

// The boxes of the terrain's drawn patches (terrainPatchBox): the terrain
// culler's clusters, one a patch.
std::vector<cull::Cluster> SceneRenderer::Impl::terrainPatchBoxes(const terrain::LodSelection& selection) const {
  std::vector<cull::Cluster> out;
  const auto count = std::uint32_t(terrain::TerrainRenderer::indexCount());
  for (const terrain::LodPatch& p : terrainRenderer->patches()) out.push_back(terrainPatchBox(*terrain, selection, p, count));
  return out;
}

// The main view's terrain with GPU culling: its selection (CPU-culled to the
// frustum by the CDLOD traversal, as without) in two halves of the drawing order,
// the first culled against the frustum alone (nothing is drawn before the
// terrain), the second against a pyramid of the first's depth. Each command is a
// run of the instance buffer's patches (cull::kInstances), so they are drawn in
// the same order as the one instanced draw.
void SceneRenderer::Impl::drawTerrainCulled(const View& view) {
  const auto selection = selectTerrain(glm::mat4(view.viewProjection), view.fovy, view.height);
  const auto prepared = terrainRenderer->prepare(selection);
  stats->drawCalls += 1;
  stats->terrainTriangles = int(prepared.trianglesDrawn);
  const auto patches = std::uint32_t(terrainRenderer->patches().size());
  terrainCuller->clearClusters();
  terrainCuller->clearJobs();
  if (patches == 0) {
    terrainCuller->upload();  // this frame's counters: zero
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    return;
  }
  const std::uint32_t first = terrainCuller->addClusters(terrainPatchBoxes(selection));
  const std::uint32_t split = patches / 2;
  cull::Job job;
  job.sphere = glm::vec4(0.0f, 0.0f, 0.0f, -1.0f);
  job.flags = cull::kInstances;
  job.firstCluster = first;
  job.clusterCount = split;
  const std::size_t near = terrainCuller->addJob(job);
  job.firstCluster = first + split;
  job.clusterCount = patches - split;
  job.firstInstance = split;
  const std::size_t far = terrainCuller->addJob(job);
  terrainCuller->upload();
  const auto uniforms = [this](const gl::Program& p) { setUniforms(p); };
  for (const std::size_t j : {near, far}) {
    cullPhase(*terrainCuller, j, j + 1, view, j == far && render.msaa <= 1);
    terrainPyramid = j == far && render.msaa <= 1;
    const IndirectDraw commands = terrainCuller->commandsOf(j);
    terrainRenderer->drawIndirect(selection, eye, uniforms, commands.offset, commands.count);
  }
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
}

// What the transmissive draws refract: the view's colour so far (sky, terrain and
// opaque draws; MSAA resolved by the blit), with its mip chain for rough surfaces.
void SceneRenderer::Impl::copyTransmissionSource() {
  glBlitNamedFramebuffer(drawFbo.id(), transmissionFbo.id(), 0, 0, targetWidth, targetHeight, 0, 0, targetWidth,
                         targetHeight, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glGenerateTextureMipmap(transmissionSource.id());
}

// Every character placed for a view from `cameraPosition`: only its root moves, the
// pose (and its palettes) stay as update left them.
void SceneRenderer::Impl::placeCharacters(const glm::dvec3& cameraPosition) {
  eye = cameraPosition;
  for (auto& c : characters) c.instance->place(c.world, cameraPosition);
}

// Each character's level-of-detail budget, from the main camera and for every pass
// of the frame: a shadow cast by another level than the one drawn would not fit
// its caster. Levels state their error relative to the diagonal of the bounds of
// every pose (ModelAsset::levelsOfDetail), the instance's bounding sphere's
// diameter: on screen, at most that error times the diameter's size in pixels at
// the sphere's nearest point.
void SceneRenderer::Impl::chooseLevelsOfDetail(const glm::dvec3& cameraPosition, double fovy, int height,
                                               double nearPlane) {
  const double pixelsAtOne = double(height) / (2.0 * std::tan(fovy / 2.0));
  for (CharacterDraw& c : characters) {
    const glm::dvec3 center = glm::dvec3(c.world * glm::dvec4(c.localCenter, 1.0));
    const double distance = std::max(glm::length(center - cameraPosition) - c.localRadius, nearPlane);
    const double diameterPixels = 2.0 * c.localRadius * pixelsAtOne / distance;
    c.instance->setLodBudget(render.lodPixels > 0.0 ? float(render.lodPixels / diameterPixels) : 0.0f);
  }
}

// "lod(within 1 px: 4672 triangles > 2336 (0.0012) > 1168 (0.0094))": each
// primitive with levels, its triangles and each level's, with its error (relative
// to the model's size in any pose).
std::string SceneRenderer::Impl::describeLevelsOfDetail() const {
  std::ostringstream out;
  out << "lod(within " << render.lodPixels << " px:";
  std::set<const CharacterAsset*> seen;
  int described = 0;
  for (const CharacterDraw& c : characters) {
    if (!seen.insert(&c.instance->asset()).second) continue;
    for (const auto& mesh : c.instance->asset().gpu.meshes())
      for (const GpuPrimitive& p : mesh) {
        if (p.levels.empty()) continue;
        out << (described++ ? ";" : "") << " " << p.indexCount / 3 << " triangles";
        for (const GpuPrimitive::Level& l : p.levels)
          out << " > " << l.indexCount / 3 << " (" << std::setprecision(2) << l.error << ")";
      }
  }
  if (described == 0) out << " no mesh has levels";
  out << ")";
  return out.str();
}

// Each probe's six faces, seen from the mirror's centre without the mirror itself.
// Positions stay camera-relative, now to the probe's centre. The sun's maps are
// drawn again around the probe: the camera's maps cover what the camera sees, and
// a static scene keeps its probes however far the camera then goes. Probes show no
// mirrors: one bounce, where the ray tracer follows --max-depth bounces. Before the
// camera's own sun maps, which this overwrites.
Status SceneRenderer::Impl::renderProbes(const glm::dvec3& cameraPosition) {
  const glm::dmat4 projection = reverseZProjection(glm::half_pi<double>(), 1.0, kProbeNear, scene.camera.farPlane);
  const glm::vec3 background = scene.sky.background;
  for (const Probe& probe : probes) {
    placeCharacters(probe.center);
    if (sunShadows) {
      // All around the probe, as far as the camera's maps reach ahead of it.
      const ShadowSphere nearSphere{glm::dvec3(0.0), std::min(scene.camera.farPlane, kSunShadowDistance)};
      const ShadowSphere farSphere{glm::dvec3(0.0), std::min(scene.camera.farPlane, kSunFarShadowDistance)};
      if (auto s = renderSunShadow(nearSphere, farSphere, glm::half_pi<double>(), probeSize); !s) return s;
    }
    glViewport(0, 0, probeSize, probeSize);
    for (int face = 0; face < 6; ++face) {
      View view;
      view.viewProjection = projection * glm::lookAt(glm::dvec3(0.0), kCubeFaceDirections[face], kCubeFaceUps[face]);
      frustumPlanes(view.viewProjection, view.planes);
      view.fovy = glm::half_pi<double>();
      view.height = probeSize;
      fillFrame(probe.center, glm::mat4(view.viewProjection));
      glNamedFramebufferTextureLayer(probeFbo.id(), GL_COLOR_ATTACHMENT0, probe.cube.id(), 0, face);
      probeFbo.bind();
      applyPassState(opaquePassFor(false));  // depth writes on, for the clear
      glClearColor(background.r, background.g, background.b, 1.0f);
      glClearDepth(0.0);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      if (auto s = drawWorld(view, probe.shape, false); !s) return s;
    }
  }
  placeCharacters(cameraPosition);
  return Ok{};
}

SceneRenderer::SceneRenderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) { impl_->stats = &stats_; }
SceneRenderer::~SceneRenderer() = default;

Result<std::unique_ptr<SceneRenderer>> SceneRenderer::create(std::shared_ptr<Scene> source,
                                                             const SceneRenderOptions& options) {
  auto impl = std::make_unique<Impl>();
  impl->scene = source->desc();
  impl->source = std::move(source);
  std::unique_ptr<SceneRenderer> renderer(new SceneRenderer(std::move(impl)));
  if (auto s = renderer->impl_->init(options); !s) return s.error();
  return renderer;
}

Result<std::unique_ptr<SceneRenderer>> SceneRenderer::create(const SceneDesc& scene, const SceneRenderOptions& options) {
  auto source = Scene::load(scene);
  if (!source) return source.error();
  return create(std::move(source).value(), options);
}

const SceneDesc& SceneRenderer::scene() const { return impl_->scene; }

const EnvironmentLighting* SceneRenderer::environmentLighting() const {
  return impl_->environmentLighting ? &*impl_->environmentLighting : nullptr;
}

std::vector<CharacterInstance*> SceneRenderer::characters() {
  std::vector<CharacterInstance*> out;
  for (auto& c : impl_->characters) out.push_back(c.instance.get());
  return out;
}

Status SceneRenderer::update(double time) {
  const auto start = std::chrono::steady_clock::now();
  if (auto s = impl_->source->update(time, impl_->rotations); !s) return s;
  const auto instances = impl_->source->instances();
  for (size_t i = 0; i < impl_->characters.size(); ++i) impl_->characters[i].instance->setPose(instances[i].pose);
  impl_->animationMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return Ok{};
}

void SceneRenderer::setPose(int instance, const Pose& pose) {
  impl_->source->setPose(instance, pose);
  impl_->characters[size_t(instance)].instance->setPose(pose);
}

Camera SceneRenderer::initialCamera() const {
  Camera camera;
  const CameraDesc& d = impl_->scene.camera;
  camera.position = d.position;
  camera.fovyDegrees = d.fovyDegrees;
  camera.nearPlane = d.nearPlane;
  camera.farPlane = d.farPlane;
  camera.lookAt(d.position + d.forward);
  return camera;
}

void SceneRenderer::Impl::beginTimer(const std::string& pass) {
  auto it = std::find_if(timers.begin(), timers.end(), [&](const PassTimer& t) { return t.pass == pass; });
  if (it == timers.end()) it = timers.insert(timers.end(), PassTimer{pass, gl::Query::create(GL_TIME_ELAPSED)});
  activeTimer = it->pending ? -1 : int(it - timers.begin());
  if (activeTimer >= 0) it->query.begin();
}

void SceneRenderer::Impl::endTimer() {
  if (activeTimer < 0) return;
  timers[size_t(activeTimer)].query.end();
  timers[size_t(activeTimer)].pending = true;
  activeTimer = -1;
}

void SceneRenderer::Impl::collectTimers() {
  for (PassTimer& t : timers) {
    if (!t.pending || !t.query.available()) continue;
    t.ms = double(t.query.result()) * 1e-6;
    t.pending = false;
  }
}

std::vector<PassTime> SceneRenderer::passTimes() const {
  impl_->collectTimers();
  std::vector<PassTime> out;
  for (const auto& t : impl_->timers) out.push_back({t.pass, t.ms});
  return out;
}

Status SceneRenderer::render(const Camera& camera, int width, int height) {
  stats_ = SceneStats{};
  stats_.animationMs = impl_->animationMs;
  Impl& s = *impl_;
  // The query spans the whole frame, and is ended even when a pass fails.
  if (!s.primitives) s.primitives = gl::Query::create(GL_PRIMITIVES_GENERATED);
  s.primitives.begin();
  Status status = s.renderFrame(camera, width, height);
  s.primitives.end();
  s.primitivesValid = true;
  return status;
}

// The skin cache's pass: every character's pose deformed once, before any pass
// draws it.
Status SceneRenderer::Impl::deformCharacters() {
  for (CharacterDraw& c : characters) {
    if (auto s = c.instance->prepare(skinModeOf(c.desc)); !s) return s;
    stats->verticesDeformed += c.instance->skinCache() ? c.instance->skinCache()->verticesDeformed() : 0;
  }
  return Ok{};
}

Status SceneRenderer::Impl::renderFrame(const Camera& camera, int width, int height) {
  GLint callerFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &callerFramebuffer);
  const bool intoCaller =
      directOutput && takesDirectFrame(gl::framebufferLayout(GLuint(callerFramebuffer)), width, height);
  if (intoCaller) {
    targetWidth = width;
    targetHeight = height;
  } else if (auto status = makeTarget(width, height); !status) {
    return status;
  }
  const glm::dvec3 cameraPosition = camera.position;
  const double aspect = double(width) / double(height);
  const double fovy = glm::radians(camera.fovyDegrees);
  const glm::dmat4 view = viewRotation(camera.forward(), scene.camera.up, scene.camera.leftHanded);
  const glm::dmat4 projection = reverseZProjection(fovy, aspect, camera.nearPlane, camera.farPlane);
  const glm::dmat4 viewProjection = projection * view;
  glm::dvec4 planes[6];
  frustumPlanes(viewProjection, planes);

  placeCharacters(cameraPosition);
  chooseLevelsOfDetail(cameraPosition, fovy, targetHeight, camera.nearPlane);
  if (terrain) measureTerrain(fovy, targetHeight);
  // Shadow passes use only their own light matrix, but every scene program declares
  // the frame block: keep it bound; it is filled once, after the sun's matrix exists.
  glBindBufferBase(GL_UNIFORM_BUFFER, gl::binding::kFrameBlock, frameUbo.id());
  collectTimers();
  if (skinPrograms && !characters.empty()) {
    beginTimer("skinning");
    const Status status = deformCharacters();
    endTimer();
    if (!status) return status;
  }
  if (pointShadows && !(pointShadowValid && characters.empty())) {
    beginTimer("shadow-point");
    const Status status = renderPointShadow(cameraPosition);
    endTimer();
    if (!status) return status;
    pointShadowValid = true;
  }
  // Probes depend on the scene, not on the camera: a scene where nothing moves
  // draws them once.
  if (!probes.empty() && !(probesValid && characters.empty())) {
    beginTimer("reflection-probes");
    const Status status = renderProbes(cameraPosition);
    endTimer();
    if (!status) return status;
    probesValid = true;
  }
  if (sunShadows) {
    const double farPlane = scene.camera.farPlane, nearPlane = camera.nearPlane;
    const ShadowSphere nearSphere =
        frustumSlice(view, fovy, aspect, nearPlane, std::min(farPlane, kSunShadowDistance));
    const ShadowSphere farSphere =
        frustumSlice(view, fovy, aspect, nearPlane, std::min(farPlane, kSunFarShadowDistance));
    beginTimer("shadow-sun");
    const Status status = renderSunShadow(nearSphere, farSphere, fovy, targetHeight);
    endTimer();
    if (!status) return status;
  }
  fillFrame(cameraPosition, glm::mat4(viewProjection));

  glBindFramebuffer(GL_FRAMEBUFFER, intoCaller ? GLuint(callerFramebuffer) : drawFbo.id());
  glViewport(0, 0, targetWidth, targetHeight);
  glDisable(GL_FRAMEBUFFER_SRGB);
  applyPassState(opaquePassFor(scene.camera.leftHanded));  // depth writes on, for the clear
  const glm::vec3 background = directOutput ? displayValue(scene.sky.background, render.output) : scene.sky.background;
  glClearColor(background.r, background.g, background.b, 1.0f);
  glClearDepth(0.0);  // reverse-Z: far is 0
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  View mainView;
  mainView.mirrored = scene.camera.leftHanded;
  mainView.main = true;
  mainView.viewProjection = viewProjection;
  std::copy(std::begin(planes), std::end(planes), std::begin(mainView.planes));
  mainView.fovy = fovy;
  mainView.height = targetHeight;
  beginTimer("world");
  const Status world = drawWorld(mainView, -1, true);
  endTimer();
  if (!world) return world;
  if (directOutput) {
    // Display values already: drawn into the caller's framebuffer, or copied into it
    // as they are.
    glClearDepth(1.0);
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(callerFramebuffer));
    glViewport(0, 0, width, height);
    if (!intoCaller) {
      stats->frameCopies = 1;
      glBlitNamedFramebuffer(drawFbo.id(), GLuint(callerFramebuffer), 0, 0, targetWidth, targetHeight, 0, 0, width,
                             height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    applyPassState(kCallerState);
    return Ok{};
  }
  beginTimer("post");

  if (render.msaa > 1) {
    glBlitNamedFramebuffer(drawFbo.id(), resolveFbo.id(), 0, 0, targetWidth, targetHeight, 0, 0,
                           targetWidth, targetHeight, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }
  // Post: into the framebuffer the caller bound. It receives display values, so
  // sRGB encoding on write is off (the shader applies the output curve itself).
  applyPassState(kPostPass);
  stats->frameCopies = 1;
  glClearDepth(1.0);
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(callerFramebuffer));
  glViewport(0, 0, width, height);
  glDisable(GL_FRAMEBUFFER_SRGB);
  post.use();
  post.set("u_exposure", render.exposure);
  hdr.bind(gl::binding::kHdr);
  emptyVao.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  endTimer();
  applyPassState(kCallerState);
  stats->drawCalls += 1;
  return Ok{};
}

CullStats SceneRenderer::cullStats() const {
  CullStats out;
  if (!impl_->culler) return out;
  const cull::Counters c = impl_->culler->counters();
  out.enabled = true;
  out.instancesTested = c.instancesTested;
  out.instancesFrustum = c.instancesFrustum;
  out.instancesOccluded = c.instancesOccluded;
  out.clustersTested = c.clustersTested;
  out.clustersFrustum = c.clustersFrustum;
  out.clustersOccluded = c.clustersOccluded;
  if (impl_->terrainCuller) {
    const cull::Counters t = impl_->terrainCuller->counters();
    out.patchesTested = t.clustersTested;
    out.patchesFrustum = t.clustersFrustum;
    out.patchesOccluded = t.clustersOccluded;
  }
  return out;
}

long long SceneRenderer::lastFrameTriangles() const {
  return impl_->primitivesValid ? static_cast<long long>(impl_->primitives.result()) : 0;
}

// "skinning(skin cache: 3 primitives, 4210 vertices, 197 KiB)": what the skin
// cache holds across every instance.
std::string SceneRenderer::Impl::describeSkinCache() const {
  int entries = 0;
  long long vertices = 0;
  std::size_t bytes = 0;
  for (const CharacterDraw& c : characters) {
    const SkinCache* cache = c.instance->skinCache();
    if (!cache) continue;
    entries += cache->entries();
    vertices += cache->verticesDeformed();
    bytes += cache->bytes();
  }
  std::ostringstream out;
  out << "skinning(skin cache: " << entries << " primitives, " << vertices << " vertices, " << (bytes + 1023) / 1024
      << " KiB)";
  return out.str();
}

namespace {
constexpr const char* kDebugViewNames[] = {"none",      "normal",    "uv",       "basecolor", "metallic",
                                           "roughness", "occlusion", "emissive", "alpha"};
}  // namespace

const char* debugViewName(DebugView view) { return kDebugViewNames[int(view)]; }

std::optional<DebugView> parseDebugView(const std::string& name) {
  for (int i = 0; i < int(std::size(kDebugViewNames)); ++i)
    if (name == kDebugViewNames[i]) return DebugView(i);
  return std::nullopt;
}

std::string debugViewList() {
  std::string list;
  for (const char* name : kDebugViewNames) list += (list.empty() ? "" : ", ") + std::string(name);
  return list;
}

std::string SceneRenderer::describe() const {
  const Impl& s = *impl_;
  std::ostringstream out;
  out << "passes:";
  if (s.sunShadows) out << " shadow-sun(" << s.sunShadowSize << ", " << (s.pcfRadius ? "pcf " + std::to_string(2 * s.pcfRadius + 1) : std::string("hard")) << ")";
  if (s.sunFarShadows) out << " shadow-sun-far(" << s.sunShadowSize << ", terrain, " << kSunFarShadowDistance << " m)";
  if (s.pointShadows) out << " shadow-point(cube " << s.cubeSize << ", " << (s.pcfRadius ? "pcf " + std::to_string(2 * s.pcfRadius + 1) : std::string("hard")) << ")";
  if (!s.probes.empty()) out << " reflection-probes(" << s.probes.size() << " x cube " << s.probeSize << ")";
  if (s.scene.sky.enabled) out << " sky";
  if (s.skyImage) {
    out << "(image " << std::filesystem::path(s.scene.sky.image).filename().string() << " " << s.skyImage.width() << "x"
        << s.skyImage.height() << ")";
  }
  if (s.environmentLighting) out << " " << ambientName(s.ambient) << "(" << s.environmentLighting->describe() << ")";
  if (s.skinPrograms) out << " " << s.describeSkinCache();
  if (s.render.lodPixels > 0.0) out << " " << s.describeLevelsOfDetail();
  if (s.terrain) out << " terrain(cdlod, " << s.terrainError << " px)";
  out << " opaque";
  if (s.scene.fog.enabled) out << "+fog";
  if (s.culler) {
    out << " gpu-culling(" << s.culler->clusters().size() << " clusters of <= " << cull::kClusterTriangles
        << " triangles; " << (s.render.msaa > 1 ? "frustum only (msaa)" : "frustum + hi-z, occluder prepass")
        << (s.terrainCuller ? "; terrain patches too" : "") << ")";
  }
  if (s.transmissionPass) out << " transmission(copy + mips)";
  if (s.blendPass) out << " blend(sorted)";
  if (s.directOutput) {
    out << " direct(display values from the fragment shaders, RGBA8, no post pass; into the caller's framebuffer"
           " when it is single-sample RGBA8 with float depth, else copied)";
  } else {
    out << " post(msaa " << s.render.msaa << ", supersample " << s.render.supersample << ")";
  }
  if (s.debugView != DebugView::None) out << "\ndebug view: " << debugViewName(s.debugView) << " (no exposure, no tone map)";
  out << "\nshading: " << (s.render.shading == Shading::Classic ? "classic" : "pbr");
  if (s.render.shading == Shading::Pbr) {
    out << ", ambient " << ambientName(s.ambient);
    if (s.environmentLighting) out << " (built once in " << std::fixed << std::setprecision(1) << s.iblMilliseconds << " ms)";
  }
  out << "\nvariants:";
  for (const auto& v : s.variants->built()) out << " " << v.describe();
  if (s.skinPrograms) {
    out << "\nskin-cache variants:";
    for (const auto& v : s.skinPrograms->built()) out << " " << v.describe();
  }
  out << "\nlast frame: " << stats_.drawCalls << " draw calls, " << stats_.programChanges << " program changes (" << stats_.programsNeeded << " needed), "
      << stats_.objectsDrawn << " objects drawn, " << stats_.objectsCulled << " culled";
  if (s.terrain) out << ", " << stats_.terrainTriangles << " terrain triangles";
  out << "\n";
  return out.str();
}

}  // namespace engine
