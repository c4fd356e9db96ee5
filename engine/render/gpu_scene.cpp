#include "render/gpu_scene.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <set>
#include <sstream>

#include "render/scene_stats.h"
#include "render/textures.h"
#include "scene/shapes.h"

namespace engine {
namespace {

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

// Whether an instance deforms in the skin cache. render.skinning auto sends it
// there where each vertex would otherwise be deformed again at a price in every
// pass that draws it (measured: bench/morph_cost, bench/skinning_cost): morph
// targets (8 of them cost 1.5x the frame in the vertex shaders, 1.1-1.2x cached),
// dual quaternions, or more than the view and one sun map drawing it (a point
// light's six cube faces, the probes). Plain LBS under a sun stays in the vertex
// shaders, cheaper there than a dispatch that writes 48 bytes a vertex.
bool usesSkinCache(const ModelData& model, const ModelDesc& desc, const GpuSceneOptions& options) {
  if (options.skinning == Skinning::Vertex) return false;
  bool skins = false, morphs = false;
  for (const NodeData& node : model.nodes) {
    if (node.mesh < 0) continue;
    for (const PrimitiveData& prim : model.meshes[size_t(node.mesh)].primitives) {
      skins = skins || (node.skin >= 0 && prim.influences > 0 && !desc.unskinned);
      morphs = morphs || prim.morphTargets > 0;
    }
  }
  if (options.skinning == Skinning::Compute) return skins || morphs;
  return morphs || (skins && (desc.dualQuat || options.manyPasses));
}

}  // namespace

Result<std::unique_ptr<GpuScene>> GpuScene::create(std::shared_ptr<Scene> source, const SceneDesc& scene,
                                                   const GpuSceneOptions& options) {
  std::unique_ptr<GpuScene> gpu(new GpuScene);
  gpu->source_ = std::move(source);
  gpu->options_ = options;
  const Scene& from = *gpu->source_;
  if (const FloatImage* image = from.images().sky.get(); image && scene.sky.enabled)
    gpu->skyImage_ = uploadSkyImage(*image);
  // Decoded once by the scene layer (scene/scene_images.h), referred to by its
  // material table (scene/materials.h), uploaded per renderer.
  for (const SceneMaterial& m : from.materials()) {
    const Image* image = m.texture(TextureSlot::BaseColor).decoded;
    gpu->materialTextures_.push_back(image ? uploadTexture(*image, true) : gl::Texture{});
  }
  if (auto s = gpu->loadModels(scene, options); !s) return s.error();
  gpu->addShapes(scene);
  for (int i = 0; i < int(options.probeShapes.size()); ++i) gpu->shapes_[size_t(options.probeShapes[size_t(i)])].probe = i;
  return gpu;
}

// One upload per model file, one CharacterInstance per scene instance.
Status GpuScene::loadModels(const SceneDesc& scene, const GpuSceneOptions& options) {
  std::vector<std::shared_ptr<const CharacterAsset>> uploaded;
  for (const auto& asset : source_->assets()) {
    auto created = CharacterAsset::create(asset, options.levelsOfDetail);
    if (!created) return makeError(scene.path + ": " + asset->model.path + ": " + created.error().message);
    uploaded.push_back(std::move(created).value());
  }
  for (const ModelInstance& instance : source_->instances()) {
    CharacterDraw draw;
    draw.instance = std::make_unique<CharacterInstance>(uploaded[size_t(instance.asset)]);
    draw.instance->setPose(instance.pose);
    draw.desc = instance.desc;
    if (options.skinModeOverride) {
      draw.desc.dualQuat = *options.skinModeOverride == SkinMode::DualQuat;
      draw.desc.unskinned = *options.skinModeOverride == SkinMode::None;
    }
    const ModelData& model = draw.instance->asset().model;
    if (usesSkinCache(model, draw.desc, options)) {
      if (!skinPrograms_) skinPrograms_ = std::make_unique<SkinPrograms>(options.shaderDir);
      draw.instance->useSkinCache(skinPrograms_.get());
    }
    for (const NodeData& node : model.nodes) {
      if (node.mesh < 0) continue;
      for (const PrimitiveData& prim : model.meshes[size_t(node.mesh)].primitives) {
        const SceneMaterial& material = draw.instance->asset().gpu.material(prim.material);
        blends_ = blends_ || material.blends();
        refracts_ = refracts_ || material.transmissive();
      }
    }
    draw.world = instance.world;
    draw.localCenter = instance.boundsCenter;
    draw.localRadius = instance.boundsRadius;
    characters_.push_back(std::move(draw));
  }
  return Ok{};
}

void GpuScene::addShapes(const SceneDesc& scene) {
  for (const PrimitiveDesc& p : scene.primitives) {
    ShapeDraw draw;
    draw.material = p.material;
    draw.world = primitiveTransform(p, scene.camera.farPlane);
    std::unique_ptr<GpuMesh>& mesh =
        p.type == PrimitiveType::Sphere ? sphere_ : p.type == PrimitiveType::Box ? cube_ : quad_;
    if (!mesh) mesh = std::make_unique<GpuMesh>(shapeForPrimitive(p));
    draw.mesh = mesh.get();
    const cull::Cluster& whole = mesh->clusters()[mesh->clusterRange().first + mesh->clusterRange().count];
    draw.lo = glm::dvec3(std::numeric_limits<double>::max());
    draw.hi = glm::dvec3(std::numeric_limits<double>::lowest());
    for (int i = 0; i < 8; ++i) {
      const glm::dvec3 corner(i & 1 ? whole.hi.x : whole.lo.x, i & 2 ? whole.hi.y : whole.lo.y,
                              i & 4 ? whole.hi.z : whole.lo.z);
      const glm::dvec3 placed(draw.world * glm::dvec4(corner, 1.0));
      draw.lo = glm::min(draw.lo, placed);
      draw.hi = glm::max(draw.hi, placed);
    }
    if (p.type == PrimitiveType::Sphere) {
      draw.center = p.center;
      draw.radius = p.radius;
    } else if (p.type == PrimitiveType::Box) {
      draw.center = (p.min + p.max) * 0.5;
      draw.radius = 0.5 * glm::length(p.max - p.min);
    } else {
      // The quad's uv spans 2 units; one texture tile per `1 / texture_scale` metres.
      const double extent = planeExtent(p, scene.camera.farPlane);
      draw.uvScale = glm::vec2(float(extent) * source_->materials()[size_t(p.material)].surface.textureScale);
      draw.twoSided = true;
    }
    shapes_.push_back(draw);
  }
}

std::vector<const GpuMesh*> GpuScene::meshes() const {
  std::vector<const GpuMesh*> out;
  for (const GpuMesh* mesh : {sphere_.get(), cube_.get(), quad_.get()})
    if (mesh) out.push_back(mesh);
  return out;
}

void GpuScene::takePoses() {
  const auto instances = source_->instances();
  for (size_t i = 0; i < characters_.size(); ++i) characters_[i].instance->setPose(instances[i].pose);
}

void GpuScene::setPose(int instance, const Pose& pose) {
  source_->setPose(instance, pose);
  characters_[size_t(instance)].instance->setPose(pose);
}

void GpuScene::place(const glm::dvec3& eye) {
  eye_ = eye;
  for (auto& c : characters_) c.instance->place(c.world, eye);
}

// Each character's level-of-detail budget, from the main camera and for every pass
// of the frame: a shadow cast by another level than the one drawn would not fit
// its caster. Levels state their error relative to the diagonal of the bounds of
// every pose (ModelAsset::levelsOfDetail), the instance's bounding sphere's
// diameter: on screen, at most that error times the diameter's size in pixels at
// the sphere's nearest point.
void GpuScene::chooseLevelsOfDetail(const glm::dvec3& cameraPosition, double fovy, int height, double nearPlane,
                                    double lodPixels) {
  const double pixelsAtOne = double(height) / (2.0 * std::tan(fovy / 2.0));
  for (CharacterDraw& c : characters_) {
    const glm::dvec3 center = glm::dvec3(c.world * glm::dvec4(c.localCenter, 1.0));
    const double distance = std::max(glm::length(center - cameraPosition) - c.localRadius, nearPlane);
    const double diameterPixels = 2.0 * c.localRadius * pixelsAtOne / distance;
    c.instance->setLodBudget(lodPixels > 0.0 ? float(lodPixels / diameterPixels) : 0.0f);
  }
}

Status GpuScene::deform(SceneStats& stats) {
  for (CharacterDraw& c : characters_) {
    if (auto s = c.instance->prepare(skinModeOf(c.desc)); !s) return s;
    stats.verticesDeformed += c.instance->skinCache() ? c.instance->skinCache()->verticesDeformed() : 0;
  }
  return Ok{};
}

std::pair<glm::dvec3, double> GpuScene::placedSphere(const CharacterDraw& c) const {
  const glm::dvec3 center = glm::dvec3(c.world * glm::dvec4(c.localCenter, 1.0)) - eye_;
  const glm::dmat3 linear(c.world);
  return {center, c.localRadius * std::max({glm::length(linear[0]), glm::length(linear[1]), glm::length(linear[2])})};
}

glm::mat4 GpuScene::shapeModel(const ShapeDraw& s) const {
  glm::dmat4 relative = s.world;
  relative[3] -= glm::dvec4(eye_, 0.0);
  return glm::mat4(relative);
}

std::size_t GpuScene::triangles(const DrawItem& item) const {
  if (item.source == DrawItem::Source::Shape) return std::size_t(shapes_[size_t(item.object)].mesh->indexCount()) / 3;
  const CharacterAsset& asset = characters_[size_t(item.object)].instance->asset();
  const int mesh = asset.model.nodes[size_t(item.node)].mesh;
  const GpuPrimitive& prim = asset.gpu.meshes()[size_t(mesh)][size_t(item.primitive)];
  return std::size_t(prim.indexCount > 0 ? prim.indexCount : prim.vertexCount) / 3;
}

// "skinning(skin cache: 3 primitives, 4210 vertices, 197 KiB)": what the skin
// cache holds across every instance.
std::string GpuScene::describeSkinCache() const {
  int entries = 0;
  long long vertices = 0;
  std::size_t bytes = 0;
  for (const CharacterDraw& c : characters_) {
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

// "lod(within 1 px: 4672 triangles > 2336 (0.0012) > 1168 (0.0094))": each
// primitive with levels, its triangles and each level's, with its error (relative
// to the model's size in any pose).
std::string GpuScene::describeLevelsOfDetail(double lodPixels) const {
  std::ostringstream out;
  out << "lod(within " << lodPixels << " px:";
  std::set<const CharacterAsset*> seen;
  int described = 0;
  for (const CharacterDraw& c : characters_) {
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

}  // namespace engine
