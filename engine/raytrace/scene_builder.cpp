#include "raytrace/scene_builder.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>

#include "anim/model_builder.h"
#include "raytrace/ground_split.h"
#include "raytrace/tone_map.h"
#include "scene/scene.h"
#include "scene/terrain_mesh.h"
#include "terrain/materials.h"
#include "terrain/page_pool.h"
#include "terrain/terrain.h"

namespace engine::rt {

namespace {

// A model's materials from the scene layer's table (ModelAsset::materials,
// scene/materials.h), which the rasterizer's uniforms read too, and after them glTF's
// default material, for its primitives without one (as the rasterizer draws them).
Result<std::vector<int>> addMaterials(const ModelAsset& asset, RtScene& scene) {
  std::vector<int> materials;  // glTF material -> RtScene material; last: the default
  for (const SceneMaterial& m : asset.materials) {
    auto material = scene.addSceneMaterial(m);
    if (!material) return material.error();
    materials.push_back(*material);
  }
  auto fallback = scene.addSceneMaterial(gltfDefaultMaterial());
  if (!fallback) return fallback.error();
  materials.push_back(*fallback);
  return materials;
}

// The parts of a primitive's traced mesh that never change: material, uvs and
// indices (a non-indexed primitive gets 0, 1, 2, ...); positions and normals sized.
RtMesh staticMesh(const PrimitiveData& prim, std::span<const int> materials) {
  RtMesh mesh;
  mesh.material = prim.material >= 0 ? materials[size_t(prim.material)] : materials.back();
  mesh.positions.resize(prim.positions.size());
  if (!prim.normals.empty()) mesh.normals.resize(prim.normals.size());
  mesh.uvs = prim.uvs;
  mesh.uvs1 = prim.uvs1;
  mesh.colors = prim.colors;
  if (prim.indices.empty()) {
    for (std::uint32_t i = 0; i < std::uint32_t(prim.positions.size()); ++i) mesh.indices.push_back(i);
  } else {
    mesh.indices = prim.indices;
  }
  return mesh;
}

void reverseWinding(std::vector<std::uint32_t>& indices) {
  for (std::size_t i = 0; i + 2 < indices.size(); i += 3) std::swap(indices[i + 1], indices[i + 2]);
}

// One model instance of the scene, in its pose, into `meshes`, one per triangle
// primitive and EXT_mesh_gpu_instancing instance of its node: positions and normals
// morphed, then skinned (or moved rigidly by node world * instance, as the
// rasterizer draws it) into world space by the instance's root; material and
// indices are filled the first time only, as they never change.
Status skinInstance(const ModelAsset& asset, std::span<const int> materials, const ModelInstance& instance,
                    std::vector<RtMesh>& meshes) {
  const ModelData& model = asset.model;
  const Skeleton& skeleton = asset.animated.skeleton;
  std::vector<glm::mat4> joints(instance.pose.joints.size());
  for (size_t j = 0; j < joints.size(); ++j) joints[j] = glm::mat4(instance.world * glm::dmat4(instance.pose.joints[j]));
  const SkinningMethod method = instance.desc.dualQuat ? SkinningMethod::DualQuat : SkinningMethod::Linear;
  const bool first = meshes.empty();
  std::size_t next = 0;
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const NodeData& node = model.nodes[n];
    if (node.mesh < 0) continue;
    const glm::mat4& nodeWorld = joints[size_t(skeleton.jointOfRaw(int(n)))];
    for (const glm::mat4& local : meshInstances(node)) {
      for (const PrimitiveData& prim : model.meshes[size_t(node.mesh)].primitives) {
        if (prim.mode != 4) continue;  // triangles only
        const bool skinned = node.skin >= 0 && prim.influences > 0;
        if (first) {
          meshes.push_back(staticMesh(prim, materials));
          // glTF: where the transform the rasterizer draws with mirrors (negative
          // determinant), clockwise faces are the front. Hits take their front
          // side from the winding, so a mirrored mesh's triangles are turned back.
          const glm::mat4 placement = skinned ? glm::mat4(instance.world) : nodeWorld * local;
          if (glm::determinant(glm::mat3(placement)) < 0.0f) reverseWinding(meshes.back().indices);
        }
        RtMesh& mesh = meshes[next++];
        const PrimitivePose pose{asset.animated.morphs.of(instance.pose.morphWeights, int(n)),
                                 skinned ? &asset.animated.skins[size_t(node.skin)] : nullptr, joints,
                                 nodeWorld * local, method};
        if (!posePrimitive(prim, pose, mesh.positions, mesh.normals)) {
          return makeError(model.path + ": node " + std::to_string(n) + ": morphing or skinning failed");
        }
      }
    }
  }
  return Ok{};
}

// Adds `mesh` to its group, and first the triangles of it that lie behind `ground`
// (when there is one) to group `behindGroup`, made at the first such triangle
// (raytrace/ground_split.h).
Status addSplitAtGround(RtMesh mesh, const std::optional<GroundPlane>& ground, int& behindGroup, RtScene& scene) {
  if (ground) {
    RtMesh behind = takeTrianglesBehind(mesh, *ground);
    if (!behind.indices.empty()) {
      if (behindGroup < 0) behindGroup = scene.addGroup("behind the ground");
      behind.group = behindGroup;
      if (auto added = scene.addMesh(std::move(behind)); !added) return added.error();
    }
  }
  if (mesh.indices.empty()) return Ok{};
  if (auto added = scene.addMesh(std::move(mesh)); !added) return added.error();
  return Ok{};
}

// The terrain as the rasterizer draws it from the scene's camera: the scene layer's
// selection for this view (scene/terrain_mesh.h), unculled, with the rasterizer's
// target and page budget, each patch a grid of morphed vertices in world space.
// What lies behind the scene's ground goes to group `behindGroup`.
Status addTerrain(const SceneDesc& desc, const terrain::Terrain& field, const TerrainView& view, RtScene& scene,
                  SceneBuildStats& stats, int& behindGroup) {
  // Every block the view's ranges need, as the rasterizer measures them, so that a
  // still of one matches a still of the other.
  measureTerrain(field, view);
  const auto selection = selectTerrain(field, view);
  // terrain.frag's material: the layers per hit (RtTerrainMaterial), full diffuse,
  // the scene's ambient and a shininess of 24 in the classic model.
  MaterialDesc layered;
  layered.name = "terrain";
  layered.color = glm::vec3(1.0f);
  layered.ambient = desc.ambient;
  layered.diffuse = 1.0f;
  layered.shininess = terrain::kLayerShininess;
  const int material = scene.addMaterial(layered);
  const auto heightScale = std::max(field.heightRange().max, 1e-3f);
  if (auto s = scene.setTerrainMaterial(material, RtTerrainMaterial(field.origin().y, heightScale)); !s) return s;
  const std::optional<GroundPlane> ground = groundPlane(desc);
  for (TerrainPatchMesh& patch : terrainPatchMeshes(field, selection, view.eye)) {
    RtMesh mesh;
    mesh.material = material;
    mesh.positions = std::move(patch.positions);
    mesh.uvs = std::move(patch.uvs);
    mesh.normals = std::move(patch.normals);
    mesh.indices = terrainPatchIndices();
    stats.triangles += int(mesh.indices.size() / 3);
    ++stats.meshes;
    if (auto added = addSplitAtGround(std::move(mesh), ground, behindGroup, scene); !added) return added;
  }
  return Ok{};
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

Result<AnimatedRtScene> AnimatedRtScene::create(std::shared_ptr<Scene> source, int viewportHeight,
                                                SceneBuildStats* statsOut, const CameraDesc* camera,
                                                double terrainErrorOverride) {
  SceneDesc desc = source->desc();
  if (camera) desc.camera = *camera;
  auto scene = RtScene::fromSceneDesc(desc, source->materials(), source->environment());
  if (!scene) return scene.error();
  AnimatedRtScene out;
  out.scene_ = std::move(scene).value();
  out.source_ = std::move(source);
  RtScene& rt = out.scene_;
  SceneBuildStats stats;
  const auto start = std::chrono::steady_clock::now();
  for (const auto& asset : out.source_->assets()) {
    auto materials = addMaterials(*asset, rt);
    if (!materials) return makeError(desc.path + ": " + asset->model.path + ": " + materials.error().message);
    out.materials_.push_back(std::move(materials).value());
  }
  const auto instances = out.source_->instances();
  for (size_t i = 0; i < instances.size(); ++i) {
    const std::string where = desc.path + ": /models/" + std::to_string(i);
    Instance instance;
    instance.group = rt.addGroup(std::filesystem::path(out.source_->assetOf(instances[i]).model.path).filename().string());
    if (auto s = out.skin(i, instance.meshes); !s) return makeError(where + ": " + s.error().message);
    for (const RtMesh& mesh : instance.meshes) {
      RtMesh copy = mesh;
      copy.group = instance.group;
      stats.triangles += int(copy.indices.size() / 3);
      ++stats.meshes;
      auto added = rt.addMesh(std::move(copy));
      if (!added) return makeError(where + ": " + added.error().message);
      instance.ids.push_back(*added);
    }
    out.instances_.push_back(std::move(instance));
  }
  int behindGroup = -1;  // the static triangles behind the scene's ground
  if (const terrain::Terrain* field = out.source_->terrain()) {
    TerrainView view;
    view.eye = desc.camera.position;
    view.fovY = glm::radians(desc.camera.fovyDegrees);
    view.viewportHeight = viewportHeight;
    view.errorPixels = terrainErrorTarget(desc, terrainErrorOverride);
    // The rasterizer's default pool: a selection it would coarsen is coarsened here too.
    view.maxPages = std::size_t(terrain::defaultPageSlots());
    if (auto s = addTerrain(desc, *field, view, rt, stats, behindGroup); !s) return s.error();
  }
  stats.skinSeconds = secondsSince(start);
  stats.bvhSeconds = rt.buildGroup(0);
  if (behindGroup >= 0) stats.bvhSeconds += rt.buildGroup(behindGroup);
  for (const Instance& instance : out.instances_) {
    InstanceStats is;
    for (const RtMesh& mesh : instance.meshes) is.triangles += int(mesh.indices.size() / 3);
    is.bvhSeconds = rt.buildGroup(instance.group);
    stats.bvhSeconds += is.bvhSeconds;
    stats.instances.push_back(is);
  }
  if (statsOut) *statsOut = stats;
  return out;
}

Result<AnimatedRtScene> AnimatedRtScene::create(const SceneDesc& desc, double time, int viewportHeight,
                                                SceneBuildStats* stats) {
  auto source = Scene::load(desc);
  if (!source) return source.error();
  if (auto s = (*source)->update(time); !s) return s.error();
  return create(std::move(source).value(), viewportHeight, stats);
}

Status AnimatedRtScene::skin(size_t index, std::vector<RtMesh>& meshes) const {
  const ModelInstance& instance = source_->instances()[index];
  return skinInstance(source_->assetOf(instance), materials_[size_t(instance.asset)], instance, meshes);
}

// The skinning time includes the scene layer's sampling of every pose.
Status AnimatedRtScene::setTime(double time, SceneBuildStats* statsOut) {
  SceneBuildStats stats;
  const auto poseStart = std::chrono::steady_clock::now();
  if (auto s = source_->update(time); !s) return s;
  const double poseSeconds = secondsSince(poseStart);
  for (size_t i = 0; i < instances_.size(); ++i) {
    Instance& instance = instances_[i];
    InstanceStats is;
    const auto start = std::chrono::steady_clock::now();
    if (auto s = skin(i, instance.meshes); !s) return s;
    for (std::size_t k = 0; k < instance.meshes.size(); ++k) {
      if (auto s = scene_.updateMesh(instance.ids[k], instance.meshes[k].positions, instance.meshes[k].normals); !s) {
        return s;
      }
      is.triangles += int(instance.meshes[k].indices.size() / 3);
    }
    is.skinSeconds = secondsSince(start) + poseSeconds / double(instances_.size());
    is.bvhSeconds = scene_.refitGroup(instance.group);
    stats.skinSeconds += is.skinSeconds;
    stats.bvhSeconds += is.bvhSeconds;
    stats.triangles += is.triangles;
    stats.meshes += int(instance.meshes.size());
    stats.instances.push_back(is);
  }
  if (statsOut) *statsOut = stats;
  return Ok{};
}

AnimatedRtScene::AnimatedRtScene() = default;
AnimatedRtScene::~AnimatedRtScene() = default;
AnimatedRtScene::AnimatedRtScene(AnimatedRtScene&&) noexcept = default;
AnimatedRtScene& AnimatedRtScene::operator=(AnimatedRtScene&&) noexcept = default;

Result<RtScene> analyticRtScene(const SceneDesc& desc) {
  auto images = SceneImages::load(desc);
  if (!images) return images.error();
  return RtScene::fromSceneDesc(desc, *images);
}

Result<RtScene> buildRtScene(const SceneDesc& desc, double time, int viewportHeight, SceneBuildStats* stats) {
  auto animated = AnimatedRtScene::create(desc, time, viewportHeight, stats);
  if (!animated) return animated.error();
  return std::move(animated->scene());
}

Result<RaytraceRun> raytraceScene(const SceneDesc& desc, double time, const RenderSettings& settings) {
  RaytraceRun run;
  auto scene = buildRtScene(desc, time, settings.height, &run.build);
  if (!scene) return scene.error();
  run.result = Integrator(*scene, settings).render();
  run.image = toImage(run.result.image, scene->render());
  return run;
}

}  // namespace engine::rt
