#pragma once
// What the ray tracer traces: analytic spheres and planes, triangle meshes in world
// space, lights, materials, camera and sky. Built from the SceneDesc the rasterizer
// also reads; the caller adds meshes (skinned characters, terrain) and, per frame,
// moves their vertices and calls refit() (or build() when triangles change).
//
// The composition of the material table (rt_materials.h: materials, their textures
// and what a hit shades with) and the acceleration structure (rt_accel.h: the shapes,
// the meshes' BVH groups and the ray queries over them) with the lights, camera,
// environment, render settings and fog. Its calls forward to the two, which are
// documented there; what needs both (transmittance) is its own.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "asset/model_data.h"
#include "asset/scene_desc.h"
#include "core/result.h"
#include "raytrace/bvh.h"
#include "raytrace/environment.h"
#include "raytrace/ray.h"
#include "raytrace/rt_accel.h"
#include "raytrace/rt_materials.h"
#include "raytrace/shape_lanes.h"
#include "raytrace/shapes.h"
#include "raytrace/terrain_material.h"
#include "raytrace/texture.h"
#include "scene/environment.h"
#include "scene/scene_images.h"

namespace engine::rt {

class RtScene {
 public:
  RtScene();  // one default material, no shapes, no lights, the default camera
  // Spheres, planes, boxes (as 12 triangles each), lights, materials, camera, sky and
  // render settings. Models and terrain are the caller's to add as meshes.
  // The scene file's materials come from the scene layer's table (scene/materials.h,
  // Scene::materials(): one per desc.materials), the lights and the sky from its
  // environment (scene/environment.h, Scene::environment(): the models' lights
  // included), not from desc.
  static Result<RtScene> fromSceneDesc(const SceneDesc& desc, std::span<const SceneMaterial> materials,
                                       const SceneEnvironment& environment);
  // The same, the table and the environment made from `images` (scene/scene_images.h)
  // as Scene::load makes them, for a scene without models.
  static Result<RtScene> fromSceneDesc(const SceneDesc& desc, const SceneImages& images);

  // The materials: RtMaterials (rt_materials.h).
  using MaterialExtras = rt::MaterialExtras;
  int addMaterial(const MaterialDesc& material) { return materialTable_.addMaterial(material); }
  Result<int> addSceneMaterial(const SceneMaterial& material) { return materialTable_.addSceneMaterial(material); }
  Status setMaterialTexture(int material, RtTexture texture) {
    return materialTable_.setMaterialTexture(material, std::move(texture));
  }
  Status setMaterialAlpha(int material, AlphaMode mode, float factor, float cutoff) {
    return materialTable_.setMaterialAlpha(material, mode, factor, cutoff);
  }
  Status setEmissiveTexture(int material, RtTexture texture) {
    return materialTable_.setEmissiveTexture(material, std::move(texture));
  }
  Status setMetallicRoughnessTexture(int material, RtTexture texture) {
    return materialTable_.setMetallicRoughnessTexture(material, std::move(texture));
  }
  Status setSingleSided(int material, bool singleSided) { return materialTable_.setSingleSided(material, singleSided); }
  Status setUnlit(int material, bool unlit) { return materialTable_.setUnlit(material, unlit); }
  Status setLayerTexture(int material, TextureSlot slot, RtTexture texture) {
    return materialTable_.setLayerTexture(material, slot, std::move(texture));
  }
  bool singleSided(int material) const { return materialTable_.singleSided(material); }
  float opacityAt(int material, const HitUv& uv, float footprint = 0.0f) const {
    return materialTable_.opacityAt(material, uv, footprint);
  }
  float surfaceOpacity(int material, const HitUv& uv, float footprint, bool backFacing) const {
    return materialTable_.surfaceOpacity(material, uv, footprint, backFacing);
  }
  bool hasTransparency() const { return materialTable_.hasTransparency(); }
  bool hasSingleSided() const { return materialTable_.hasSingleSided(); }
  bool hasTextures() const { return materialTable_.hasTextures(); }
  Status setTerrainMaterial(int material, RtTerrainMaterial layers) {
    return materialTable_.setTerrainMaterial(material, std::move(layers));
  }
  HitMaterial baseMaterial(int material) const { return materialTable_.baseMaterial(material); }
  HitMaterial materialAt(int material, const HitUv& uv, float footprint, double y, const glm::vec3& ns,
                         const glm::vec3& dpdu = glm::vec3(0.0f), const glm::vec3& dpdv = glm::vec3(0.0f)) const {
    return materialTable_.materialAt(material, uv, footprint, y, ns, dpdu, dpdv);
  }
  const std::vector<MaterialDesc>& materials() const { return materialTable_.materials(); }
  const MaterialExtras& extras(int material) const { return materialTable_.extras(material); }
  const std::vector<RtTexture>& textures() const { return materialTable_.textures(); }
  const std::vector<RtTerrainMaterial>& terrains() const { return materialTable_.terrains(); }

  // The first sun also draws the gradient sky's disk (SceneEnvironment::sun).
  void addLight(const LightDesc& light);
  void setCamera(const CameraDesc& camera) { camera_ = camera; }
  // The sky's gradient (with the first sun light's disk) or background colour. An
  // image sky is not loaded here, as loading can fail: build it with
  // Environment::create and give it to setEnvironment.
  void setSky(const SkyDesc& sky);
  // What escaping rays see from now on, whatever the sky and the lights say.
  void setEnvironment(Environment environment);
  void setRender(const RenderDesc& render) { render_ = render; }
  void setFog(const FogDesc& fog) { fog_ = fog; }
  void setAtmosphere(const AtmosphereDesc& atmosphere) { atmosphere_ = atmosphere; }
  void setMedia(std::vector<MediumDesc> media) { media_ = std::move(media); }

  // The shapes and meshes and the queries over them: RtAccel (rt_accel.h).
  void addSphere(const glm::dvec3& center, double radius, int material) { accel_.addSphere(center, radius, material); }
  void addPlane(const glm::dvec3& point, const glm::dvec3& normal, int material, double extent = 0.0) {
    accel_.addPlane(point, normal, material, extent);
  }
  int addGroup(std::string name = {}) { return accel_.addGroup(std::move(name)); }
  std::string groupName(int group) const { return accel_.groupName(group); }
  // Also checks that the mesh's material is one of the scene's.
  Result<MeshId> addMesh(RtMesh mesh) { return accel_.addMesh(std::move(mesh), int(materials().size())); }
  Status updateMesh(MeshId id, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals = {}) {
    return accel_.updateMesh(id, positions, normals);
  }
  void clearMeshes() { accel_.clearMeshes(); }
  double build() { return accel_.build(); }
  double refit() { return accel_.refit(); }
  double buildGroup(int group) { return accel_.buildGroup(group); }
  double refitGroup(int group) { return accel_.refitGroup(group); }

  template <typename T>
  std::optional<SurfaceInteraction<T>> intersect(const Ray<T>& ray) const {
    return accel_.intersect(ray, materialTable_);
  }
  void intersectMany(const Ray<float>* const* rays, std::size_t count,
                     std::optional<SurfaceInteraction<float>>* out) const {
    accel_.intersectMany(rays, count, out, materialTable_);
  }
  void intersectCoherent(std::span<const Ray<float>, Bvh::kPacketSize> rays,
                         std::span<std::optional<SurfaceInteraction<float>>, Bvh::kPacketSize> out) const {
    accel_.intersectCoherent(rays, out, materialTable_);
  }
  bool eightRaysAtATime() const { return accel_.eightRaysAtATime(); }
  template <typename T>
  bool intersectAny(const Ray<T>& ray) const {
    return accel_.intersectAny(ray);
  }
  // The share of light that passes along a shadow ray: 0 or 1 past opaque surfaces
  // (an any-hit ray), the product of 1 - opacity past cut-away and transparent ones
  // (exact, not stochastic). `target`: the ray ends there (d = target - o, tMax 1);
  // null: it goes to tMax along d. `rays` counts the rays traced.
  template <typename T>
  float transmittance(const Ray<T>& ray, const Vec3<T>* target, std::uint64_t& rays) const;

  const CameraDesc& camera() const { return camera_; }
  const std::vector<LightDesc>& lights() const { return lights_; }
  const SkyDesc& sky() const { return sky_; }
  const Environment& environment() const { return environment_; }
  // PBR's hemisphere ambient (see ambientSkyColor in asset/scene_desc.h).
  glm::vec3 ambientSky() const { return ambientSky_; }
  glm::vec3 ambientGround() const { return ambientGround_; }
  const RenderDesc& render() const { return render_; }
  const FogDesc& fog() const { return fog_; }
  // The planet's atmosphere and the bounded media: the path tracer's (raytrace/media.h).
  const AtmosphereDesc& atmosphere() const { return atmosphere_; }
  const std::vector<MediumDesc>& media() const { return media_; }
  // The rasterizer's distance fog (shaders/scene.frag, common/fog.glsl) on a colour the
  // camera sees at `distance`: mix(fog colour, colour, exp(-density * distance)). It
  // is the scene's look, not a medium: no light scatters in it, in either tracer.
  glm::vec3 fogged(const glm::vec3& color, float distance) const {
    if (!fog_.enabled) return color;
    return glm::mix(fog_.color, color, std::clamp(std::exp(-fog_.density * distance), 0.0f, 1.0f));
  }
  const std::vector<RtMesh>& meshes() const { return accel_.meshes(); }
  int groupCount() const { return accel_.groupCount(); }
  const Bvh& bvh(int group = 0) const { return accel_.bvh(group); }
  std::size_t triangleCount() const { return accel_.triangleCount(); }
  const std::vector<Sphere<float>>& floatSpheres() const { return accel_.floatSpheres(); }
  const std::vector<Plane<float>>& floatPlanes() const { return accel_.floatPlanes(); }
  using PlaneSquare = rt::PlaneSquare;
  const PlaneSquare& planeSquare(std::size_t plane) const { return accel_.planeSquare(plane); }
  const std::vector<std::uint32_t>& groupTriangleMeshes(int group) const { return accel_.groupTriangleMeshes(group); }
  std::uint32_t meshFirstTriangle(MeshId mesh) const { return accel_.meshFirstTriangle(mesh); }
  std::size_t sphereCount() const { return accel_.sphereCount(); }
  const ShapeLanes& shapeLanes() const { return accel_.shapeLanes(); }
  std::size_t planeCount() const { return accel_.planeCount(); }

 private:
  // The sun whose disk the gradient sky draws: the first sun light, the one the
  // rasterizer's sky draws (SceneEnvironment::sun).
  std::optional<glm::vec3> sunDirection() const;
  void rebuildGradientSky();

  RtMaterials materialTable_;
  RtAccel accel_;
  CameraDesc camera_;
  std::vector<LightDesc> lights_;
  SkyDesc sky_;
  Environment environment_;
  // Whether environment_ follows sky_ and the lights (false after setEnvironment).
  bool environmentFromSky_ = true;
  glm::vec3 ambientSky_{0.1f};
  glm::vec3 ambientGround_{0.1f};
  RenderDesc render_;
  FogDesc fog_;
  AtmosphereDesc atmosphere_;
  std::vector<MediumDesc> media_;
};

}  // namespace engine::rt
