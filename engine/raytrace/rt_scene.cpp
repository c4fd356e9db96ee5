#include "raytrace/rt_scene.h"

#include "core/brdf.h"
#include "scene/shapes.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <limits>
#include <string>
#include <type_traits>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace engine::rt {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A box as the rasterizer draws it: scene/shapes.h's unit cube (12 triangles, per
// face the normal and two axes, counter-clockwise from outside, corners at uv (0,0)
// (1,0) (1,1) (0,1)) placed by the same transform, flat shaded, uv times the
// material's texture scale.
RtMesh boxMesh(const PrimitiveDesc& box, int material, float uvScale) {
  const ShapeData cube = shapeForPrimitive(box);
  const glm::dmat4 transform = primitiveTransform(box, 0.0);
  RtMesh mesh;
  mesh.material = material;
  for (const Vertex& v : cube.vertices) {
    mesh.positions.emplace_back(glm::vec3(transform * glm::dvec4(glm::dvec3(v.position), 1.0)));
    mesh.uvs.emplace_back(v.uv * uvScale);
  }
  mesh.indices = cube.indices;
  return mesh;
}

// The rasterizer's sphere (render/mesh.cpp makeSphere): n = (sin t sin p, cos t,
// sin t cos p) at uv = (p / 2 pi, t / pi).
glm::vec2 sphereUv(const glm::dvec3& n) {
  const double theta = std::acos(std::clamp(n.y, -1.0, 1.0));
  double phi = std::atan2(n.x, n.z);
  if (phi < 0.0) phi += 2.0 * glm::pi<double>();
  return glm::vec2(float(phi / (2.0 * glm::pi<double>())), float(theta / glm::pi<double>()));
}

// A per-vertex attribute is absent (empty) or has one value per position.
Status checkPerVertex(std::size_t values, std::size_t positions, const std::string& where, const char* what) {
  if (values == 0 || values == positions) return Ok{};
  return makeError(where + ": " + std::to_string(values) + " " + what + " for " + std::to_string(positions) +
                   " positions");
}

// A per-vertex attribute at a triangle hit, weighted by its barycentrics in float.
template <typename V, typename Hit>
V atHit(const std::vector<V>& values, const Hit& hit, std::uint32_t i0, std::uint32_t i1, std::uint32_t i2) {
  return float(hit.b0) * values[i0] + float(hit.b1) * values[i1] + float(hit.b2) * values[i2];
}

float maxAbs(const glm::vec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

}  // namespace

RtScene::RtScene() {
  MaterialDesc fallback;
  fallback.name = "default";
  materials_.push_back(fallback);
  extras_.emplace_back();
  rebuildGradientSky();
}

std::optional<glm::vec3> RtScene::sunDirection() const {
  std::optional<glm::vec3> sun;
  for (const LightDesc& l : lights_) {
    if (l.type == LightType::Sun) sun = glm::normalize(glm::vec3(l.direction));
  }
  return sun;
}

void RtScene::rebuildGradientSky() {
  SkyDesc gradient = sky_;
  gradient.image.clear();
  // Without an image nothing is loaded, so this cannot fail.
  environment_ = std::move(Environment::create(gradient, sunDirection())).value();
}

void RtScene::addLight(const LightDesc& light) {
  lights_.push_back(light);
  if (light.type == LightType::Sun && environmentFromSky_ && sky_.image.empty()) rebuildGradientSky();
}

void RtScene::setSky(const SkyDesc& sky) {
  assert(sky.image.empty() && "an image sky is loaded by Environment::create, then setEnvironment");
  sky_ = sky;
  environmentFromSky_ = true;
  rebuildGradientSky();
}

void RtScene::setEnvironment(Environment environment) {
  environment_ = std::move(environment);
  environmentFromSky_ = false;
}

Result<RtScene> RtScene::fromSceneDesc(const SceneDesc& desc, const SceneImages& images) {
  RtScene scene;
  if (!desc.materials.empty()) scene.materials_ = desc.materials;
  scene.extras_.assign(scene.materials_.size(), MaterialExtras{});
  for (size_t i = 0; i < desc.materials.size(); ++i) {
    const Image* image = images.materialTexture(i);
    // The rasterizer uploads the scene's textures flipped: uv (0, 0) is the bottom-left.
    if (!image) continue;
    if (auto s = scene.setMaterialTexture(int(i), RtTexture(*image, TextureOrigin::BottomLeft)); !s) return s.error();
  }
  scene.camera_ = desc.camera;
  scene.lights_ = desc.lights;
  scene.sky_ = desc.sky;
  auto environment = Environment::create(desc.sky, scene.sunDirection(), images.sky);
  if (!environment) return makeError(desc.path + ": /sky/image: " + environment.error().message);
  scene.environment_ = std::move(environment).value();
  scene.ambientSky_ = ambientSkyColor(desc);
  scene.ambientGround_ = ambientGroundColor(desc);
  scene.render_ = desc.render;
  scene.fog_ = desc.fog;
  const int materialCount = int(scene.materials_.size());
  for (std::size_t i = 0; i < desc.primitives.size(); ++i) {
    const PrimitiveDesc& p = desc.primitives[i];
    if (p.material < 0 || p.material >= materialCount) {
      return makeError(desc.path + ": primitive " + std::to_string(i) + ": material " +
                       std::to_string(p.material) + " out of range");
    }
    switch (p.type) {
      case PrimitiveType::Sphere:
        scene.addSphere(p.center, p.radius, p.material);
        break;
      case PrimitiveType::Plane:
        scene.addPlane(p.point, p.normal, p.material, planeExtent(p, desc.camera.farPlane));
        break;
      case PrimitiveType::Box: {
        auto id = scene.addMesh(boxMesh(p, p.material, scene.materials_[size_t(p.material)].textureScale));
        if (!id) return id.error();
        break;
      }
    }
  }
  scene.build();
  return scene;
}

int RtScene::addMaterial(const MaterialDesc& material) {
  materials_.push_back(material);
  extras_.emplace_back().dielectricF0 = material.layers.dielectricF0();
  return int(materials_.size() - 1);
}

Status RtScene::checkMaterial(int material) const {
  if (material < 0 || material >= int(materials_.size())) {
    return makeError("material " + std::to_string(material) + " out of range");
  }
  return Ok{};
}

// Stores the texture and points the material's `slot` at it.
Status RtScene::attachTexture(int material, int MaterialExtras::*slot, RtTexture texture) {
  if (auto s = checkMaterial(material); !s) return s.error();
  extras_[size_t(material)].*slot = int(textures_.size());
  textures_.push_back(std::move(texture));
  return Ok{};
}

Status RtScene::setMaterialTexture(int material, RtTexture texture) {
  return attachTexture(material, &MaterialExtras::texture, std::move(texture));
}

glm::vec3 RtScene::baseColor(int material, const HitUv& uv, float footprint) const {
  const glm::vec3 color = materials_[size_t(material)].color * glm::vec3(uv.color);
  const int texture = extras_[size_t(material)].texture;
  return texture < 0 ? color : color * textures_[size_t(texture)].sample(uv, footprint);
}

Status RtScene::setMaterialAlpha(int material, AlphaMode mode, float factor, float cutoff) {
  if (auto s = checkMaterial(material); !s) return s.error();
  MaterialExtras& e = extras_[size_t(material)];
  e.alphaMode = mode;
  e.alpha = factor;
  e.alphaCutoff = cutoff;
  if (mode != AlphaMode::Opaque) transparent_ = true;
  return Ok{};
}

Status RtScene::setMetallicRoughnessTexture(int material, RtTexture texture) {
  return attachTexture(material, &MaterialExtras::metallicRoughnessTexture, std::move(texture));
}

Status RtScene::setSingleSided(int material, bool singleSided) {
  if (auto s = checkMaterial(material); !s) return s.error();
  extras_[size_t(material)].singleSided = singleSided;
  if (singleSided) singleSided_ = true;
  return Ok{};
}

Status RtScene::setUnlit(int material, bool unlit) {
  if (auto s = checkMaterial(material); !s) return s.error();
  extras_[size_t(material)].unlit = unlit;
  return Ok{};
}

Status RtScene::setLayerTexture(int material, TextureSlot slot, RtTexture texture) {
  if (auto s = checkMaterial(material); !s) return s.error();
  if (int(slot) < kFirstLayerSlot || int(slot) >= kTextureSlots) return makeError("not a layer texture slot");
  MaterialExtras& e = extras_[size_t(material)];
  e.layerTextures[size_t(slot) - kFirstLayerSlot] = int(textures_.size());
  e.hasLayerTextures = true;
  textures_.push_back(std::move(texture));
  return Ok{};
}

// glTF's layer textures at a hit, applied to `out`'s dielectric f0 and f90, coat,
// transmission, thickness and sheen.
void RtScene::applyLayerTextures(int material, const HitUv& uv, float footprint, HitMaterial& out) const {
  const auto& t = extras_[size_t(material)].layerTextures;
  auto at = [&](TextureSlot slot) -> const RtTexture* {
    const int i = t[size_t(slot) - kFirstLayerSlot];
    return i >= 0 ? &textures_[size_t(i)] : nullptr;
  };
  const MaterialLayers& layers = materials_[size_t(material)].layers;
  const RtTexture* specular = at(TextureSlot::Specular);
  const RtTexture* specularColor = at(TextureSlot::SpecularColor);
  if (specular || specularColor) {
    const float weight = layers.specular * (specular ? specular->sampleRgba(uv, footprint).a : 1.0f);
    const glm::vec3 color = layers.specularColor * (specularColor ? specularColor->sample(uv, footprint) : glm::vec3(1.0f));
    out.dielectricF0 = layers.dielectricF0(color, weight);
    out.dielectricF90 = weight;
  }
  if (const RtTexture* coat = at(TextureSlot::Clearcoat)) out.clearcoat *= coat->sample(uv, footprint).x;
  if (const RtTexture* rough = at(TextureSlot::ClearcoatRoughness)) out.clearcoatRoughness *= rough->sample(uv, footprint).y;
  if (const RtTexture* share = at(TextureSlot::Transmission)) out.transmission *= share->sample(uv, footprint).x;
  if (const RtTexture* thick = at(TextureSlot::Thickness)) out.thickness *= thick->sample(uv, footprint).y;
  if (const RtTexture* sheen = at(TextureSlot::SheenColor)) out.sheenColor *= sheen->sample(uv, footprint);
  if (const RtTexture* rough = at(TextureSlot::SheenRoughness)) out.sheenRoughness *= rough->sampleRgba(uv, footprint).a;
  if (const RtTexture* stretch = at(TextureSlot::Anisotropy)) {
    const glm::vec3 texel = stretch->sample(uv, footprint);
    out.anisotropyDirection = glm::vec2(texel) * 2.0f - 1.0f;
    out.anisotropy *= texel.z;
  }
  if (const RtTexture* film = at(TextureSlot::Iridescence)) out.iridescence *= film->sample(uv, footprint).x;
  if (const RtTexture* thick = at(TextureSlot::IridescenceThickness)) {
    out.iridescenceThickness =
        glm::mix(layers.iridescenceThicknessMin, layers.iridescenceThicknessMax, thick->sample(uv, footprint).y);
  }
}

namespace {

// KHR_materials_anisotropy's stretch in world space: the tangent frame of the
// triangle's uv gradient (the tangent MikkTSpace builds, flat across the triangle and
// following the posed mesh; the rasterizer interpolates the file's or the loader's
// tangents instead), the material's direction in it turned by its rotation
// (brdf.glsl's anisotropyDirection, as the rasterizer turns it).
void orientAnisotropy(HitMaterial& m, const glm::vec3& ns, const glm::vec3& dpdu, const glm::vec3& dpdv) {
  glm::vec3 t = dpdu - ns * glm::dot(ns, dpdu);
  const float len = glm::length(t);
  const glm::vec2 d = brdf::anisotropyDirection(m.anisotropyDirection, m.anisotropyRotation);
  if (len > 0.0f && std::isfinite(len)) {
    t /= len;
    // glTF's bitangent points up the image, against dP/dv (uv's v runs down it; its
    // normal maps are +Y up): the files' TANGENT handedness says the same
    // (RasterVsRaytrace.GltfAnisotropyAgrees turns on it).
    const glm::vec3 across = glm::cross(ns, t);
    const glm::vec3 b = glm::dot(across, dpdv) < 0.0f ? across : -across;
    const glm::vec3 stretched = t * d.x + b * d.y;
    const float slen = glm::length(stretched);
    if (slen > 1e-6f) {
      m.anisotropyT = stretched / slen;
      m.anisotropy = std::clamp(m.anisotropy, 0.0f, 1.0f);
      return;
    }
  }
  m.anisotropy = 0.0f;  // nothing to orient it by
}

}  // namespace

Status RtScene::setEmissiveTexture(int material, RtTexture texture) {
  return attachTexture(material, &MaterialExtras::emissiveTexture, std::move(texture));
}

float RtScene::opacityAt(int material, const HitUv& uv, float footprint) const {
  const MaterialExtras& e = extras_[size_t(material)];
  if (e.alphaMode == AlphaMode::Opaque) return 1.0f;
  const float alpha =
      e.alpha * uv.color.a * (e.texture >= 0 ? textures_[size_t(e.texture)].sampleRgba(uv, footprint).a : 1.0f);
  // MASK as scene.frag's discard: below the cutoff the surface is not there at all.
  if (e.alphaMode == AlphaMode::Mask) return alpha >= e.alphaCutoff ? 1.0f : 0.0f;
  return std::clamp(alpha, 0.0f, 1.0f);
}

Status RtScene::setTerrainMaterial(int material, RtTerrainMaterial layers) {
  if (auto s = checkMaterial(material); !s) return s.error();
  extras_[size_t(material)].terrain = int(terrains_.size());
  terrains_.push_back(std::move(layers));
  return Ok{};
}

HitMaterial RtScene::baseMaterial(int material) const {
  const MaterialDesc& m = materials_[size_t(material)];
  HitMaterial out{m.color, m.ambient, m.diffuse, m.specular, m.shininess, m.reflection,
                  m.metallic, m.roughness, m.emission, extras_[size_t(material)].unlit,
                  extras_[size_t(material)].dielectricF0, m.layers.dielectricF90(), m.layers.clearcoat,
                  m.layers.clearcoatRoughness, m.layers.transmission, m.layers.ior, m.layers.thickness,
                  m.layers.attenuationDistance, m.layers.attenuationColor, m.layers.sheenColor,
                  m.layers.sheenRoughness, m.layers.anisotropy, m.layers.anisotropyRotation};
  out.iridescence = m.layers.iridescence;
  out.iridescenceIor = m.layers.iridescenceIor;
  out.iridescenceThickness = m.layers.iridescenceThicknessMax;
  return out;
}

HitMaterial RtScene::materialAt(int material, const HitUv& uv, float footprint, double y, const glm::vec3& ns,
                                const glm::vec3& dpdu, const glm::vec3& dpdv) const {
  HitMaterial out = baseMaterial(material);
  out.albedo = baseColor(material, uv, footprint);
  if (const int mr = extras_[size_t(material)].metallicRoughnessTexture; mr >= 0) {
    const glm::vec3 t = textures_[size_t(mr)].sample(uv, footprint);
    out.roughness *= t.y;
    out.metallic *= t.z;
  }
  if (const int emissive = extras_[size_t(material)].emissiveTexture; emissive >= 0) {
    out.emission *= textures_[size_t(emissive)].sample(uv, footprint);
  }
  if (extras_[size_t(material)].hasLayerTextures) applyLayerTextures(material, uv, footprint, out);
  if (out.anisotropy > 0.0f) orientAnisotropy(out, ns, dpdu, dpdv);
  if (const int terrain = extras_[size_t(material)].terrain; terrain >= 0) {
    const TerrainLayerSample layers = terrains_[size_t(terrain)].sample(uv.uv0, footprint, y, ns.y);
    out.albedo *= layers.albedo;
    out.roughness = layers.roughness;
    out.specular = layers.specular;
  }
  return out;
}

void RtScene::addSphere(const glm::dvec3& center, double radius, int material) {
  spheresD_.push_back(Sphere<double>{center, radius, material});
  spheresF_.push_back(Sphere<float>{glm::vec3(center), float(radius), material});
  packs_.setSpheres(spheresF_);
  lanes_.addSphere(spheresF_.back());
  updateRoots();
}

void RtScene::addPlane(const glm::dvec3& point, const glm::dvec3& normal, int material, double extent) {
  const glm::dvec3 n = glm::normalize(normal);
  const glm::dmat3 r(rotationFromTo(glm::dvec3(0, 1, 0), n));
  planeUvs_.push_back(PlaneUv{point, r * glm::dvec3(1, 0, 0), r * glm::dvec3(0, 0, 1), extent});
  const double d = glm::dot(n, point);
  planesD_.push_back(Plane<double>{n, d, material});
  planesF_.push_back(Plane<float>{glm::vec3(n), float(d), material});
  std::vector<ShapePacks::Square> squares;
  for (const PlaneUv& q : planeUvs_) squares.push_back({q.point, q.extent});
  packs_.setPlanes(planesF_, squares);
  lanes_.addPlane(planesF_.back(), planeUvs_.back());
}

int RtScene::addGroup(std::string name) {
  groups_.emplace_back();
  groups_.back().name = std::move(name);
  return int(groups_.size() - 1);
}

Result<MeshId> RtScene::addMesh(RtMesh mesh) {
  const std::string where = "mesh " + std::to_string(meshes_.size());
  if (mesh.indices.size() % 3 != 0) return makeError(where + ": index count is not a multiple of 3");
  for (std::uint32_t i : mesh.indices) {
    if (i >= mesh.positions.size()) return makeError(where + ": index " + std::to_string(i) + " out of range");
  }
  if (auto s = checkPerVertex(mesh.normals.size(), mesh.positions.size(), where, "normals"); !s) return s.error();
  if (auto s = checkPerVertex(mesh.uvs.size(), mesh.positions.size(), where, "uvs"); !s) return s.error();
  if (auto s = checkPerVertex(mesh.uvs1.size(), mesh.positions.size(), where, "second-set uvs"); !s) return s.error();
  if (auto s = checkPerVertex(mesh.colors.size(), mesh.positions.size(), where, "colours"); !s) return s.error();
  if (mesh.material < 0 || mesh.material >= int(materials_.size())) {
    return makeError(where + ": material " + std::to_string(mesh.material) + " out of range");
  }
  if (mesh.group < 0 || mesh.group >= int(groups_.size())) {
    return makeError(where + ": group " + std::to_string(mesh.group) + " does not exist");
  }
  Group& group = groups_[std::size_t(mesh.group)];
  group.meshes.push_back(std::uint32_t(meshes_.size()));
  group.topologyDirty = true;
  meshes_.push_back(std::move(mesh));
  meshFirstTriangle_.push_back(0);
  return MeshId(meshes_.size() - 1);
}

Status RtScene::updateMesh(MeshId id, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals) {
  if (id < 0 || id >= MeshId(meshes_.size())) return makeError("mesh " + std::to_string(id) + ": no such mesh");
  RtMesh& mesh = meshes_[std::size_t(id)];
  if (positions.size() != mesh.positions.size()) {
    return makeError("mesh " + std::to_string(id) + ": " + std::to_string(positions.size()) + " positions, expected " +
                     std::to_string(mesh.positions.size()));
  }
  if (!normals.empty() && normals.size() != mesh.normals.size()) {
    return makeError("mesh " + std::to_string(id) + ": " + std::to_string(normals.size()) + " normals, expected " +
                     std::to_string(mesh.normals.size()));
  }
  mesh.positions.assign(positions.begin(), positions.end());
  if (!normals.empty()) mesh.normals.assign(normals.begin(), normals.end());
  groups_[std::size_t(mesh.group)].moved = true;
  return Ok{};
}

void RtScene::clearMeshes() {
  meshes_.clear();
  meshFirstTriangle_.clear();
  groups_.assign(1, Group{});
  boxedTriangles_ = false;
  updateRoots();
}

std::size_t RtScene::triangleCount() const {
  std::size_t n = 0;
  for (const Group& g : groups_) n += g.triangles.size();
  return n;
}

void RtScene::gatherTriangles(int groupIndex) {
  Group& group = groups_[std::size_t(groupIndex)];
  group.triangles.clear();
  group.triangleMesh.clear();
  for (std::uint32_t m : group.meshes) {
    const RtMesh& mesh = meshes_[m];
    meshFirstTriangle_[m] = std::uint32_t(group.triangles.size());
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
      group.triangles.push_back(TriangleVerts{mesh.positions[mesh.indices[i]], mesh.positions[mesh.indices[i + 1]],
                                              mesh.positions[mesh.indices[i + 2]]});
      group.triangleMesh.push_back(m);
    }
  }
}

double RtScene::buildGroup(int groupIndex) {
  const auto start = std::chrono::steady_clock::now();
  gatherTriangles(groupIndex);
  Group& group = groups_[std::size_t(groupIndex)];
  group.bvh.build(group.triangles);
  group.topologyDirty = group.moved = false;
  boxedTriangles_ = triangleCount() > 0;
  updateRoots();
  return secondsSince(start);
}

double RtScene::refitGroup(int groupIndex) {
  if (groups_[std::size_t(groupIndex)].topologyDirty) return buildGroup(groupIndex);
  const auto start = std::chrono::steady_clock::now();
  gatherTriangles(groupIndex);
  Group& group = groups_[std::size_t(groupIndex)];
  group.bvh.refit(group.triangles);
  group.moved = false;
  updateRoots();
  return secondsSince(start);
}

Bvh::Node RtScene::noRoots() {
  Bvh::Node node{};
  for (int lane = 0; lane < Bvh::kWidth; ++lane) {
    for (int axis = 0; axis < 3; ++axis) {
      node.box[axis][lane] = std::numeric_limits<float>::infinity();
      node.box[axis + 3][lane] = -std::numeric_limits<float>::infinity();
    }
    node.child[lane] = Bvh::kNoChild;
  }
  return node;
}

void RtScene::updateRoots() {
  roots_ = noRoots();
  Bounds3f lanes[Bvh::kWidth];
  float extent = 1.0f;
  const auto grow = [&](const Bounds3f& b) {
    if (b.empty()) return;
    extent = std::max({extent, maxAbs(b.min), maxAbs(b.max)});
  };
  for (std::size_t g = 0; g < groups_.size() && g < std::size_t(kSphereLane); ++g) {
    lanes[g] = groups_[g].bvh.bounds();
    grow(lanes[g]);
  }
  Bounds3f spheres;
  for (const Sphere<float>& s : spheresF_) {
    spheres.extend(s.center - glm::vec3(s.radius));
    spheres.extend(s.center + glm::vec3(s.radius));
  }
  grow(spheres);
  // The float sphere test may accept a ray that passes outside the sphere by its
  // rounding, a few float epsilons of the distances involved (at most the origin's,
  // within the limit, and the sphere's): 2e-5 of the limit is over a hundred times that.
  rootsOriginLimit_ = std::isfinite(extent) ? 16.0f * extent : -1.0f;
  if (!spheres.empty()) {
    const glm::vec3 margin(2e-5f * rootsOriginLimit_);
    spheres.min -= margin;
    spheres.max += margin;
  }
  lanes[kSphereLane] = spheres;
  for (int lane = 0; lane < Bvh::kWidth; ++lane) {
    for (int axis = 0; axis < 3; ++axis) {
      roots_.box[axis][lane] = lanes[lane].min[axis];
      roots_.box[axis + 3][lane] = lanes[lane].max[axis];
    }
  }
}

RtScene::RootHits RtScene::testRoots(const Ray<float>& ray) const {
  RootHits hits;
  testRoots(ray, hits);
  return hits;
}

void RtScene::testRoots(const Ray<float>& ray, RootHits& hits) const {
  hits.mask = Bvh::testBoxes(roots_, ray, ray.tMax, hits.tEntry);
  if (!(maxAbs(ray.o) <= rootsOriginLimit_)) hits.mask |= 1 << kSphereLane;
}

double RtScene::build() {
  double total = 0.0;
  for (int g = 0; g < groupCount(); ++g) total += buildGroup(g);
  return total;
}

double RtScene::refit() {
  double total = 0.0;
  for (int g = 0; g < groupCount(); ++g) {
    if (groups_[std::size_t(g)].topologyDirty || groups_[std::size_t(g)].moved) total += refitGroup(g);
  }
  return total;
}

template <>
const std::vector<Sphere<float>>& RtScene::spheres<float>() const {
  return spheresF_;
}
template <>
const std::vector<Sphere<double>>& RtScene::spheres<double>() const {
  return spheresD_;
}
template <>
const std::vector<Plane<float>>& RtScene::planes<float>() const {
  return planesF_;
}
template <>
const std::vector<Plane<double>>& RtScene::planes<double>() const {
  return planesD_;
}

// Whether a plane's hit at t lies on the square the rasterizer draws (always, for an
// unbounded plane), so that both renderers see the same ground's edge.
template <typename T>
bool RtScene::onPlaneSquare(std::size_t plane, const Ray<T>& ray, T t) const {
  const PlaneUv& q = planeUvs_[plane];
  if (q.extent <= 0.0) return true;
  if constexpr (std::is_same_v<T, float>) {
    if (packs_.clearlyOnSquare(plane, ray, t)) return true;
  }
  return q.holds(glm::dvec3(ray(t)));
}

template <typename T>
SurfaceInteraction<T> RtScene::meshInteraction(const Group& group, const BvhHit<T>& hit) const {
  const std::uint32_t meshIndex = group.triangleMesh[hit.triangle];
  const RtMesh& mesh = meshes_[meshIndex];
  const std::size_t first = 3 * std::size_t(hit.triangle - meshFirstTriangle_[meshIndex]);
  const std::uint32_t i0 = mesh.indices[first], i1 = mesh.indices[first + 1], i2 = mesh.indices[first + 2];
  SurfaceInteraction<T> si = triangleInteraction(hit.hit, Vec3<T>(mesh.positions[i0]), Vec3<T>(mesh.positions[i1]),
                                                 Vec3<T>(mesh.positions[i2]));
  if (!mesh.normals.empty()) {
    const Vec3<T> ns = hit.hit.b0 * Vec3<T>(mesh.normals[i0]) + hit.hit.b1 * Vec3<T>(mesh.normals[i1]) +
                       hit.hit.b2 * Vec3<T>(mesh.normals[i2]);
    const T len = glm::length(ns);
    if (len > T(0)) si.ns = ns / len;
  }
  if (!mesh.uvs.empty()) {
    si.uv = atHit(mesh.uvs, hit.hit, i0, i1, i2);
    const glm::vec2 du = mesh.uvs[i1] - mesh.uvs[i0], dv = mesh.uvs[i2] - mesh.uvs[i0];
    const float uvArea = std::abs(du.x * dv.y - du.y * dv.x);
    const float area = glm::length(glm::cross(mesh.positions[i1] - mesh.positions[i0], mesh.positions[i2] - mesh.positions[i0]));
    si.uvPerMetre = area > 0.0f ? std::sqrt(uvArea / area) : 0.0f;
    const float det = du.x * dv.y - dv.x * du.y;
    if (materials_[size_t(mesh.material)].layers.anisotropy > 0.0f && std::abs(det) > 0.0f) {
      const glm::vec3 e1 = mesh.positions[i1] - mesh.positions[i0], e2 = mesh.positions[i2] - mesh.positions[i0];
      si.dpdu = (dv.y * e1 - du.y * e2) / det;
      si.dpdv = (du.x * e2 - dv.x * e1) / det;
    }
  }
  si.uv1 = mesh.uvs1.empty() ? si.uv : atHit(mesh.uvs1, hit.hit, i0, i1, i2);
  if (!mesh.colors.empty()) si.color = atHit(mesh.colors, hit.hit, i0, i1, i2);
  si.material = mesh.material;
  return si;
}

template <typename T>
int RtScene::nearestShape(Ray<T>& ray, std::size_t& index, bool testSpheres) const {
  int kind = 0;
  if constexpr (std::is_same_v<T, float>) {
    if (const int sphere = testSpheres ? packs_.nearestSphere(ray, ray.tMax) : -1; sphere >= 0) {
      kind = 1;
      index = std::size_t(sphere);
    }
    packs_.forEachPlaneHit(ray, ray.tMax, [&](std::size_t plane, float t) {
      if (t < ray.tMax && onPlaneSquare(plane, ray, t)) {
        ray.tMax = t;
        kind = 2;
        index = plane;
      }
      return false;
    });
    return kind;
  }
  const auto& sphereList = spheres<T>();
  for (std::size_t i = 0; i < sphereList.size(); ++i) {
    if (auto t = sphereList[i].intersect(ray)) {
      ray.tMax = *t;
      kind = 1;
      index = i;
    }
  }
  const auto& planeList = planes<T>();
  for (std::size_t i = 0; i < planeList.size(); ++i) {
    if (auto t = planeList[i].intersect(ray); t && onPlaneSquare(i, ray, *t)) {
      ray.tMax = *t;
      kind = 2;
      index = i;
    }
  }
  return kind;
}

template <typename T>
bool RtScene::anyShape(const Ray<T>& ray, bool testSpheres) const {
  if constexpr (std::is_same_v<T, float>) {
    return (testSpheres && packs_.anySphere(ray)) ||
           packs_.forEachPlaneHit(ray, ray.tMax, [&](std::size_t plane, float t) { return onPlaneSquare(plane, ray, t); });
  }
  for (const auto& s : spheres<T>()) {
    if (s.intersect(ray)) return true;
  }
  const auto& planeList = planes<T>();
  for (std::size_t i = 0; i < planeList.size(); ++i) {
    if (auto t = planeList[i].intersect(ray); t && onPlaneSquare(i, ray, *t)) return true;
  }
  return false;
}

template <typename T>
std::optional<SurfaceInteraction<T>> RtScene::intersect(const Ray<T>& rayIn) const {
  // Member by member: a copy of the whole struct read it back in 16-byte loads over the
  // caller's narrower stores of it, a store-forwarding stall on every ray.
  Ray<T> ray{rayIn.o, rayIn.d, rayIn.tMax};
  // Which shape won: 0 none, 1 sphere, 2 plane; shapes shorten tMax as they hit.
  std::size_t index = 0;
  std::optional<SurfaceInteraction<T>> result;
  if constexpr (std::is_same_v<T, float>) {
    if (boxedTriangles_ && rootsUsable()) {
      const RootHits roots = testRoots(ray);
      const int kind = nearestShape(ray, index, roots.spheres());
      pastShapes(ray, kind, index, result, &roots);
      return result;
    }
  }
  const int kind = nearestShape(ray, index);
  pastShapes(ray, kind, index, result);
  return result;
}

bool RtScene::onSquareOf(const void* scene, std::size_t plane, const Ray<float>& ray, float t) {
  return static_cast<const RtScene*>(scene)->onPlaneSquare(plane, ray, t);
}

void RtScene::intersectMany(const Ray<float>* const* rays, std::size_t count,
                            std::optional<SurfaceInteraction<float>>* out) const {
  if (eightRaysAtATime()) {
    for (std::size_t first = 0; first < count; first += lanes8::kLanes) {
      intersectEight(rays + first, int(std::min<std::size_t>(lanes8::kLanes, count - first)), out + first);
    }
    return;
  }
  for (std::size_t first = 0; first < count; first += 4) {
    const int n = int(std::min<std::size_t>(4, count - first));
    ShapePacks::Nearest nearest[4];
    packs_.nearestOfFour(rays + first, n, nearest, onSquareOf, this);
    for (int i = 0; i < n; ++i) {
      const Ray<float>& r = *rays[first + std::size_t(i)];
      Ray<float> ray{r.o, r.d, nearest[i].tMax};
      pastShapes(ray, nearest[i].kind, std::size_t(nearest[i].index), out[first + std::size_t(i)]);
    }
  }
}

template <typename T>
void RtScene::pastShapes(Ray<T>& ray, int kind, std::size_t index, std::optional<SurfaceInteraction<T>>& result,
                         const RootHits* roots) const {
  // Each group's root box is tested against the shortened tMax first, so groups the
  // ray misses, or that lie behind the nearest hit so far, cost one box test rather
  // than a traversal's setup and its root node's eight boxes.
  result.reset();
  if (boxedTriangles_) {  // BoundsRay's three divisions only where there are boxes
    const Group* hitGroup = nullptr;
    std::optional<BvhHit<T>> meshHit;
    const auto visit = [&](const Group& group) {
      if (auto hit = group.bvh.intersect(ray)) {
        ray.tMax = hit->hit.t;
        meshHit = hit;
        hitGroup = &group;
      }
    };
    bool visited = false;
    if constexpr (std::is_same_v<T, float>) {
      if (rootsUsable()) {
        const RootHits own = roots ? RootHits{} : testRoots(ray);
        const RootHits& hits = roots ? *roots : own;
        for (std::size_t g = 0; g < groups_.size(); ++g) {
          if (hits.group(g, ray.tMax)) visit(groups_[g]);
        }
        visited = true;
      }
    }
    if (!visited) {
      const BoundsRay<T> boxes(ray);
      for (const Group& group : groups_) {
        if (boxes.hits(group.bvh.bounds(), ray)) visit(group);
      }
    }
    if (hitGroup) {
      result = meshInteraction(*hitGroup, *meshHit);
      return;
    }
  }
  shapeInteraction(ray, kind, index, result);
}

template <typename T>
void RtScene::shapeInteraction(const Ray<T>& ray, int kind, std::size_t index,
                               std::optional<SurfaceInteraction<T>>& result) const {
  if (kind == 1) {
    SurfaceInteraction<T>& si = result.emplace();
    spheres<T>()[index].fillInteraction(ray, ray.tMax, si);
    shapeUv(kind, index, si);
    return;
  }
  if (kind == 2) {
    SurfaceInteraction<T>& si = result.emplace();
    planes<T>()[index].fillInteraction(ray, ray.tMax, si);
    shapeUv(kind, index, si);
  }
}

void RtScene::intersectCoherent(std::span<const Ray<float>, Bvh::kPacketSize> rays,
                                std::span<std::optional<SurfaceInteraction<float>>, Bvh::kPacketSize> out) const {
  constexpr int kLanes = Bvh::kPacketSize;
  if (!boxedTriangles_ || !rootsUsable()) {
    for (int i = 0; i < kLanes; ++i) out[std::size_t(i)] = intersect(rays[std::size_t(i)]);
    return;
  }
  // intersect()'s steps lane by lane, each group's traversal shared: the same roots,
  // shapes and groups in the same order, each lane's tMax shortened as it goes.
  Ray<float> packet[kLanes];
  RootHits roots[kLanes];
  int kind[kLanes];
  std::size_t index[kLanes];
  for (int i = 0; i < kLanes; ++i) {
    const Ray<float>& r = rays[std::size_t(i)];
    packet[i] = Ray<float>{r.o, r.d, r.tMax};
    testRoots(packet[i], roots[i]);
  }
  if (cpuHasAvx2()) {
    nearestShapesOfEight(packet, kind, index);
  } else {
    for (int i = 0; i < kLanes; ++i) {
      index[i] = 0;
      kind[i] = nearestShape(packet[i], index[i], roots[i].spheres());
    }
  }
  const Group* hitGroup[kLanes] = {};
  BvhHit<float> meshHit[kLanes];
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    unsigned lanes = 0;
    for (int i = 0; i < kLanes; ++i) lanes |= unsigned(roots[i].group(g, packet[i].tMax)) << i;
    if (lanes == 0) continue;
    const Group& group = groups_[g];
    // Lanes that miss the group's box take no part: with tMax 0 no hit can be theirs.
    Ray<float> entering[kLanes];
    for (int i = 0; i < kLanes; ++i) entering[i] = Ray<float>{packet[i].o, packet[i].d, (lanes >> i & 1) ? packet[i].tMax : 0.0f};
    BvhHit<float> hits[kLanes];
    for (unsigned hit = group.bvh.intersect8(entering, hits) & lanes; hit != 0; hit &= hit - 1) {
      const int i = __builtin_ctz(hit);
      packet[i].tMax = hits[i].hit.t;
      meshHit[i] = hits[i];
      hitGroup[i] = &group;
    }
  }
  for (int i = 0; i < kLanes; ++i) {
    std::optional<SurfaceInteraction<float>>& result = out[std::size_t(i)];
    result.reset();
    if (hitGroup[i]) {
      result = meshInteraction(*hitGroup[i], meshHit[i]);
    } else {
      shapeInteraction(packet[i], kind[i], index[i], result);
    }
  }
}

template <typename T>
void RtScene::shapeUv(int kind, std::size_t index, SurfaceInteraction<T>& si) const {
  const float scale = materials_[size_t(si.material)].textureScale;
  const bool readsUv = extras_[size_t(si.material)].readsUv();
  if (kind == 1) {
    if (readsUv) si.uv = sphereUv(glm::dvec3(si.n)) * scale;
    // u runs once around (2 pi r), v from pole to pole (pi r): their geometric mean.
    si.uvPerMetre = scale / (float(std::numbers::pi) * std::sqrt(2.0f) * float(spheres<T>()[index].radius));
  } else {
    if (readsUv) {
      const PlaneUv& q = planeUvs_[index];
      const glm::dvec3 local = glm::dvec3(si.p) - q.point;
      si.uv = glm::vec2(glm::dvec2(glm::dot(local, q.axisU) + q.extent, glm::dot(local, q.axisV) + q.extent) *
                        double(scale));
    }
    si.uvPerMetre = scale;
  }
  si.uv1 = si.uv;
}

ENGINE_AVX2_BEGIN
namespace {

// Eight rays into lanes; lanes past count repeat the first ray. Each lane read as a
// float of its own: vector loads over the rays' (or a staging array's) scalar stores
// would wait for those stores to retire.
lanes8::Rays raysInLanes(const Ray<float>* const* rays, int count) {
  using namespace lanes8;
  const Ray<float>* r[kLanes];
  for (int i = 0; i < kLanes; ++i) r[i] = rays[i < count ? i : 0];
  const auto lanes = [&](auto field) {
    return _mm256_setr_ps(field(*r[0]), field(*r[1]), field(*r[2]), field(*r[3]), field(*r[4]), field(*r[5]),
                          field(*r[6]), field(*r[7]));
  };
  Rays out;
  out.o = {lanes([](const Ray<float>& x) { return x.o.x; }), lanes([](const Ray<float>& x) { return x.o.y; }),
           lanes([](const Ray<float>& x) { return x.o.z; })};
  out.d = {lanes([](const Ray<float>& x) { return x.d.x; }), lanes([](const Ray<float>& x) { return x.d.y; }),
           lanes([](const Ray<float>& x) { return x.d.z; })};
  out.dd = dot(out.d, out.d);
  out.tMax = lanes([](const Ray<float>& x) { return x.tMax; });
  return out;
}

}  // namespace

void RtScene::nearestShapesOfEight(Ray<float>* rays, int* kind, std::size_t* index) const {
  using namespace lanes8;
  const Ray<float>* lanes[kLanes];
  for (int i = 0; i < kLanes; ++i) lanes[i] = &rays[i];
  Rays r = raysInLanes(lanes, kLanes);
  F t;
  I shape;
  Shapes{lanes_}.nearest(r, t, shape);
  alignas(32) float tMax[kLanes];
  alignas(32) int shapes[kLanes];
  _mm256_store_ps(tMax, t);
  _mm256_store_si256(reinterpret_cast<I*>(shapes), shape);
  for (int i = 0; i < kLanes; ++i) {
    rays[i].tMax = tMax[i];
    const bool sphere = shapes[i] < int(lanes_.spheres);
    kind[i] = shapes[i] < 0 ? 0 : sphere ? 1 : 2;
    index[i] = shapes[i] < 0 ? 0 : std::size_t(shapes[i]) - (sphere ? 0 : lanes_.spheres);
  }
}

void RtScene::intersectEight(const Ray<float>* const* rays, int count,
                             std::optional<SurfaceInteraction<float>>* out) const {
  using namespace lanes8;
  Rays r = raysInLanes(rays, count);
  const Shapes shapes{lanes_};
  F t;
  I shape;
  shapes.nearest(r, t, shape);
  const Hits h = shapes.record(r, t, shape);
  alignas(32) float f[10][kLanes];
  const F columns[10] = {t, h.p.x, h.p.y, h.p.z, h.pError.x, h.pError.y, h.pError.z, h.n.x, h.n.y, h.n.z};
  for (int c = 0; c < 10; ++c) _mm256_store_ps(f[c], columns[c]);
  alignas(32) int index[kLanes], material[kLanes];
  _mm256_store_si256(reinterpret_cast<I*>(index), shape);
  _mm256_store_si256(reinterpret_cast<I*>(material), h.material);
  for (int i = 0; i < count; ++i) {
    out[i].reset();
    if (index[i] < 0) continue;
    SurfaceInteraction<float>& si = out[i].emplace();
    si.t = f[0][i];
    si.p = {f[1][i], f[2][i], f[3][i]};
    si.pError = {f[4][i], f[5][i], f[6][i]};
    si.n = si.ns = {f[7][i], f[8][i], f[9][i]};
    si.material = material[i];
    const std::size_t s = std::size_t(index[i]);
    if (s < lanes_.spheres) {
      shapeUv(1, s, si);
    } else {
      shapeUv(2, s - lanes_.spheres, si);
    }
  }
}
ENGINE_AVX2_END

template <typename T>
bool RtScene::intersectAny(const Ray<T>& ray) const {
  if constexpr (std::is_same_v<T, float>) {
    if (boxedTriangles_ && rootsUsable()) {
      const RootHits roots = testRoots(ray);
      if (anyShape(ray, roots.spheres())) return true;
      for (std::size_t g = 0; g < groups_.size(); ++g) {
        if (roots.group(g, ray.tMax) && groups_[g].bvh.intersectAny(ray)) return true;
      }
      return false;
    }
  }
  if (anyShape(ray)) return true;
  if (!boxedTriangles_) return false;  // BoundsRay's three divisions, for nothing
  const BoundsRay<T> boxes(ray);
  for (const Group& group : groups_) {
    if (boxes.hits(group.bvh.bounds(), ray) && group.bvh.intersectAny(ray)) return true;
  }
  return false;
}

template <typename T>
float RtScene::transmittance(const Ray<T>& shadowRay, const Vec3<T>* target, std::uint64_t& rays) const {
  ++rays;
  if (!transparent_) return intersectAny(shadowRay) ? 0.0f : 1.0f;
  Ray<T> ray = shadowRay;
  float share = 1.0f;
  // As many surfaces as a ray may pass elsewhere: a forest of alpha-tested leaves is
  // deep, but not this deep.
  for (int i = 0; i <= 64; ++i) {
    const std::optional<SurfaceInteraction<T>> hit = intersect(ray);
    if (!hit) return share;
    share *= 1.0f - opacityAt(hit->material, HitUv(hit->uv, hit->uv1, hit->color));
    if (share <= 0.0f) return 0.0f;
    ++rays;
    ray = target ? hit->spawnRayTo(*target, T(1)) : Ray<T>{hit->spawnRay(ray.d).o, ray.d, ray.tMax - hit->t};
  }
  return 0.0f;
}

template float RtScene::transmittance(const Ray<float>&, const Vec3<float>*, std::uint64_t&) const;
template float RtScene::transmittance(const Ray<double>&, const Vec3<double>*, std::uint64_t&) const;
template std::optional<SurfaceInteraction<float>> RtScene::intersect(const Ray<float>&) const;
template std::optional<SurfaceInteraction<double>> RtScene::intersect(const Ray<double>&) const;
template bool RtScene::intersectAny(const Ray<float>&) const;
template bool RtScene::intersectAny(const Ray<double>&) const;

}  // namespace engine::rt
