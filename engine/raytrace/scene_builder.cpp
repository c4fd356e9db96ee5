#include "raytrace/scene_builder.h"

#include <algorithm>
#include <chrono>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <optional>

#include "anim/jobs.h"
#include "anim/model_builder.h"
#include "anim/player.h"
#include "asset/gltf_loader.h"
#include "raytrace/tone_map.h"
#include "scene/instances.h"
#include "terrain/lod.h"
#include "terrain/materials.h"
#include "terrain/scene_terrain.h"
#include "terrain/terrain.h"

namespace engine::rt {

struct LoadedModel {
  ModelData model;
  AnimatedModel animated;
  std::vector<int> materials;  // glTF material -> RtScene material
};

namespace {

// glTF base colour: the factor times the texture (uploaded as is by the rasterizer,
// so uv (0, 0) is the image's top-left).
Status addMaterials(LoadedModel& loaded, RtScene& scene) {
  for (const MaterialData& m : loaded.model.materials) {
    MaterialDesc desc;
    desc.name = m.name;
    desc.color = glm::vec3(m.baseColorFactor);
    desc.metallic = m.metallicFactor;
    desc.roughness = m.roughnessFactor;
    desc.specular = 0.5f * (1.0f - m.roughnessFactor);
    desc.emission = m.emissiveFactor;
    const int material = scene.addMaterial(desc);
    if (m.baseColorImage >= 0) {
      const RtTexture texture(loaded.model.images[size_t(m.baseColorImage)].image, TextureOrigin::TopLeft);
      if (auto s = scene.setMaterialTexture(material, texture); !s) return s;
    }
    if (m.emissiveImage >= 0) {
      const RtTexture emissive(loaded.model.images[size_t(m.emissiveImage)].image, TextureOrigin::TopLeft);
      if (auto s = scene.setEmissiveTexture(material, emissive); !s) return s;
    }
    if (m.metallicRoughnessImage >= 0) {
      const RtTexture mr(loaded.model.images[size_t(m.metallicRoughnessImage)].image, TextureOrigin::TopLeft,
                         TextureEncoding::Linear);
      if (auto s = scene.setMetallicRoughnessTexture(material, mr); !s) return s;
    }
    if (auto s = scene.setMaterialAlpha(material, m.alphaMode, m.baseColorFactor.a, m.alphaCutoff); !s) return s;
    if (auto s = scene.setSingleSided(material, !m.doubleSided); !s) return s;
    loaded.materials.push_back(material);
  }
  return Ok{};
}

// Poses one model instance at `time` into `meshes`, one per triangle primitive:
// positions and normals morphed, then skinned (or moved rigidly) into world space; material and
// indices are filled the first time only, as they never change.
Status poseInstance(const LoadedModel& loaded, const ModelDesc& desc, int clip, double time, double ground,
                    std::vector<RtMesh>& meshes) {
  const Skeleton& skeleton = loaded.animated.skeleton;
  const MorphLayout& morphs = loaded.animated.morphs;
  std::vector<Srt> locals(skeleton.restPose().begin(), skeleton.restPose().end());
  std::vector<float> weights = morphs.restWeights;
  if (clip >= 0) {
    const Clip& c = loaded.animated.clips[size_t(clip)];
    const double local = wrapTime(clipTimeAt(desc, time), c.duration(), LoopMode::Repeat);
    if (auto s = runJob(SamplingJob{&c, local, skeleton.restPose(), locals}, loaded.model.path); !s) return s;
    if (auto s = runJob(MorphSamplingJob{&c, local, morphs.restWeights, weights}, loaded.model.path); !s) return s;
  }
  std::vector<glm::mat4> models(locals.size());
  const LocalToModelJob toModel{skeleton.parents(), locals, glm::mat4(modelTransform(desc, ground)), models};
  if (auto s = runJob(toModel, loaded.model.path); !s) return s;
  const SkinningMethod method = desc.dualQuat ? SkinningMethod::DualQuat : SkinningMethod::Linear;
  const bool first = meshes.empty();
  std::size_t next = 0;
  for (size_t n = 0; n < loaded.model.nodes.size(); ++n) {
    const NodeData& node = loaded.model.nodes[n];
    if (node.mesh < 0) continue;
    const glm::mat4& world = models[size_t(skeleton.jointOfRaw(int(n)))];
    for (const PrimitiveData& prim : loaded.model.meshes[size_t(node.mesh)].primitives) {
      if (prim.mode != 4) continue;  // triangles only
      if (first) {
        RtMesh mesh;
        mesh.material = prim.material >= 0 ? loaded.materials[size_t(prim.material)] : 0;
        mesh.positions.resize(prim.positions.size());
        if (!prim.normals.empty()) mesh.normals.resize(prim.normals.size());
        mesh.uvs = prim.uvs;
        if (prim.indices.empty()) {
          for (std::uint32_t i = 0; i < std::uint32_t(prim.positions.size()); ++i) mesh.indices.push_back(i);
        } else {
          mesh.indices = prim.indices;
        }
        meshes.push_back(std::move(mesh));
      }
      RtMesh& mesh = meshes[next++];
      const bool skinned = node.skin >= 0 && prim.influences > 0;
      const PrimitivePose pose{morphs.of(weights, int(n)),
                               skinned ? &loaded.animated.skins[size_t(node.skin)] : nullptr, models, world, method};
      if (!posePrimitive(prim, pose, mesh.positions, mesh.normals)) {
        return makeError(loaded.model.path + ": node " + std::to_string(n) + ": morphing or skinning failed");
      }
    }
  }
  return Ok{};
}

// The terrain as the rasterizer draws it from the scene's camera: the CDLOD patches
// selected for this view, each a grid of morphed vertices, in world space.
Status addTerrain(const SceneDesc& desc, const terrain::Terrain& field, int viewportHeight, RtScene& scene,
                  SceneBuildStats& stats) {
  const CameraDesc& c = desc.camera;
  terrain::LodCamera camera;
  camera.position = c.position;
  camera.fovY = glm::radians(c.fovyDegrees);
  camera.viewportHeight = viewportHeight;
  camera.viewProjection = glm::mat4(glm::perspective(camera.fovY, 16.0 / 9.0, c.nearPlane, c.farPlane) *
                                    glm::lookAt(glm::dvec3(0.0), c.forward, c.up));
  // No culling: terrain outside the view still casts shadows into it.
  camera.cull = false;
  const auto selection = terrain::selectLod(field, camera, desc.terrain.errorPixels);
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
  // Layer uvs as terrain.vert makes them: camera-relative metres over the tile size
  // plus the rasterizer's offset (the far scale multiplies the whole uv, so the
  // offset must be the same).
  const glm::vec2 uvOffset = terrain::layerUvOffset(c.position - field.origin());
  const std::vector<std::uint32_t> indices = terrain::patchIndices();
  for (const auto& patch : selection.patches) {
    RtMesh mesh;
    mesh.material = material;
    for (const glm::vec3& v : terrain::patchVertices(field, selection, patch)) {
      mesh.positions.push_back(glm::vec3(glm::dvec3(v) + c.position));
      mesh.uvs.push_back(glm::vec2(v.x, v.z) / terrain::kLayerTileMetres + uvOffset);
    }
    mesh.normals = terrain::patchNormals(field, selection, patch);
    mesh.indices = indices;
    stats.triangles += int(mesh.indices.size() / 3);
    ++stats.meshes;
    auto added = scene.addMesh(std::move(mesh));
    if (!added) return added.error();
  }
  return Ok{};
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

Result<AnimatedRtScene> AnimatedRtScene::create(const SceneDesc& desc, double time, int viewportHeight,
                                                SceneBuildStats* statsOut) {
  auto scene = RtScene::fromSceneDesc(desc);
  if (!scene) return scene.error();
  AnimatedRtScene out;
  out.scene_ = std::move(scene).value();
  RtScene& rt = out.scene_;
  SceneBuildStats stats;
  const auto start = std::chrono::steady_clock::now();
  std::optional<terrain::Terrain> field;
  if (desc.terrain.enabled) {
    auto created = terrain::Terrain::create(terrain::settingsFromScene(desc.terrain));
    if (!created) return makeError(desc.path + ": /terrain: " + created.error().message);
    field.emplace(std::move(created).value());
  }
  for (size_t i = 0; i < desc.models.size(); ++i) {
    const ModelDesc& m = desc.models[i];
    const std::string where = desc.path + ": /models/" + std::to_string(i);
    auto it = out.models_.find(m.path);
    if (it == out.models_.end()) {
      auto model = loadGltf(m.path);
      if (!model) return makeError(where + "/path: " + model.error().message);
      auto animated = buildAnimatedModel(*model);
      if (!animated) return makeError(where + ": " + animated.error().message);
      auto loaded = std::make_unique<LoadedModel>(LoadedModel{std::move(model).value(), std::move(animated).value(), {}});
      if (auto s = addMaterials(*loaded, rt); !s) return makeError(where + ": " + s.error().message);
      it = out.models_.emplace(m.path, std::move(loaded)).first;
    }
    auto clip = findClip(it->second->animated, m.clip, m.path);
    if (!clip) return makeError(where + "/clip: " + clip.error().message);
    Instance instance;
    instance.model = it->second.get();
    instance.desc = m;
    instance.clip = *clip;
    instance.ground = m.onTerrain && field ? field->heightAt(m.position.x, m.position.z) : 0.0;
    instance.group = rt.addGroup();
    if (auto s = poseInstance(*instance.model, m, instance.clip, time, instance.ground, instance.meshes); !s) {
      return makeError(where + ": " + s.error().message);
    }
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
  if (field) {
    if (auto s = addTerrain(desc, *field, viewportHeight, rt, stats); !s) return s.error();
  }
  stats.skinSeconds = secondsSince(start);
  stats.bvhSeconds = rt.buildGroup(0);
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

Status AnimatedRtScene::setTime(double time, SceneBuildStats* statsOut) {
  SceneBuildStats stats;
  for (Instance& instance : instances_) {
    InstanceStats is;
    const auto start = std::chrono::steady_clock::now();
    if (auto s = poseInstance(*instance.model, instance.desc, instance.clip, time, instance.ground, instance.meshes);
        !s) {
      return s;
    }
    for (std::size_t k = 0; k < instance.meshes.size(); ++k) {
      if (auto s = scene_.updateMesh(instance.ids[k], instance.meshes[k].positions, instance.meshes[k].normals); !s) {
        return s;
      }
      is.triangles += int(instance.meshes[k].indices.size() / 3);
    }
    is.skinSeconds = secondsSince(start);
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
