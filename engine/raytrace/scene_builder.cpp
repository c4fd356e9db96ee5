#include "raytrace/scene_builder.h"

#include <chrono>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <optional>

#include "anim/jobs.h"
#include "anim/model_builder.h"
#include "anim/player.h"
#include "asset/gltf_loader.h"
#include "raytrace/tone_map.h"
#include "terrain/lod.h"
#include "terrain/scene_terrain.h"
#include "terrain/terrain.h"

namespace engine::rt {
namespace {

struct LoadedModel {
  ModelData model;
  AnimatedModel animated;
  std::vector<int> materials;  // glTF material -> RtScene material
};

// The ray tracer has no textures: a textured glTF material becomes its factor
// times the texture's mean colour (in linear space), the colour it shows from afar.
glm::vec3 meanLinearColor(const Image& image) {
  if (image.empty()) return glm::vec3(1.0f);
  glm::dvec3 sum(0.0);
  for (size_t i = 0; i < image.pixels.size(); i += 4) {
    for (int c = 0; c < 3; ++c) sum[c] += std::pow(image.pixels[i + size_t(c)] / 255.0, 2.2);
  }
  return glm::vec3(sum / double(image.pixels.size() / 4));
}

void addMaterials(LoadedModel& loaded, RtScene& scene) {
  for (const MaterialData& m : loaded.model.materials) {
    MaterialDesc desc;
    desc.name = m.name;
    glm::vec3 color(m.baseColorFactor);
    if (m.baseColorImage >= 0) color *= meanLinearColor(loaded.model.images[size_t(m.baseColorImage)].image);
    desc.color = color;
    desc.metallic = m.metallicFactor;
    desc.roughness = m.roughnessFactor;
    desc.specular = 0.5f * (1.0f - m.roughnessFactor);
    loaded.materials.push_back(scene.addMaterial(desc));
  }
}

// Poses one model instance at `time` and adds its primitives as meshes.
Status addModelInstance(const LoadedModel& loaded, const ModelDesc& desc, int clip, double time, double ground,
                        RtScene& scene, SceneBuildStats& stats) {
  const Skeleton& skeleton = loaded.animated.skeleton;
  std::vector<Srt> locals(skeleton.restPose().begin(), skeleton.restPose().end());
  if (clip >= 0) {
    const Clip& c = loaded.animated.clips[size_t(clip)];
    SamplingJob{&c, wrapTime(desc.start + time * desc.speed, c.duration(), LoopMode::Repeat), skeleton.restPose(),
                locals}
        .run();
  }
  std::vector<glm::mat4> models(locals.size());
  LocalToModelJob{skeleton.parents(), locals, glm::mat4(modelTransform(desc, ground)), models}.run();
  const SkinningMethod method = desc.dualQuat ? SkinningMethod::DualQuat : SkinningMethod::Linear;
  for (size_t n = 0; n < loaded.model.nodes.size(); ++n) {
    const NodeData& node = loaded.model.nodes[n];
    if (node.mesh < 0) continue;
    const glm::mat4& world = models[size_t(skeleton.jointOfRaw(int(n)))];
    for (const PrimitiveData& prim : loaded.model.meshes[size_t(node.mesh)].primitives) {
      if (prim.mode != 4) continue;  // triangles only
      RtMesh mesh;
      mesh.material = prim.material >= 0 ? loaded.materials[size_t(prim.material)] : 0;
      mesh.positions.resize(prim.positions.size());
      if (!prim.normals.empty()) mesh.normals.resize(prim.normals.size());
      if (node.skin >= 0 && prim.influences > 0) {
        if (!skinPrimitive(prim, loaded.animated.skins[size_t(node.skin)], models, method, mesh.positions,
                           mesh.normals)) {
          return makeError(loaded.model.path + ": skinning failed");
        }
      } else {
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(world)));
        for (size_t v = 0; v < prim.positions.size(); ++v) {
          mesh.positions[v] = glm::vec3(world * glm::vec4(prim.positions[v], 1.0f));
          if (!mesh.normals.empty()) mesh.normals[v] = glm::normalize(normalMatrix * prim.normals[v]);
        }
      }
      if (prim.indices.empty()) {
        for (std::uint32_t i = 0; i < std::uint32_t(prim.positions.size()); ++i) mesh.indices.push_back(i);
      } else {
        mesh.indices = prim.indices;
      }
      stats.triangles += int(mesh.indices.size() / 3);
      ++stats.meshes;
      auto added = scene.addMesh(std::move(mesh));
      if (!added) return added.error();
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
  MaterialDesc grass;
  grass.name = "terrain";
  grass.color = glm::vec3(0.2f, 0.32f, 0.12f);  // the grass layer's mean colour, linear
  grass.roughness = 0.9f;
  const int material = scene.addMaterial(grass);
  for (const auto& patch : selection.patches) {
    const auto vertices = terrain::patchVertices(field, selection, patch);
    const int n = int(std::lround(std::sqrt(double(vertices.size())))) - 1;
    RtMesh mesh;
    mesh.material = material;
    for (const glm::vec3& v : vertices) mesh.positions.push_back(glm::vec3(glm::dvec3(v) + c.position));
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const std::uint32_t a = std::uint32_t(j * (n + 1) + i), b = a + 1, d = a + std::uint32_t(n + 1), e = d + 1;
        mesh.indices.insert(mesh.indices.end(), {a, d, b, b, d, e});
      }
    }
    stats.triangles += int(mesh.indices.size() / 3);
    ++stats.meshes;
    auto added = scene.addMesh(std::move(mesh));
    if (!added) return added.error();
  }
  return Ok{};
}

}  // namespace

Result<RtScene> buildRtScene(const SceneDesc& desc, double time, int viewportHeight, SceneBuildStats* statsOut) {
  auto scene = RtScene::fromSceneDesc(desc);
  if (!scene) return scene.error();
  SceneBuildStats stats;
  const auto start = std::chrono::steady_clock::now();
  std::optional<terrain::Terrain> field;
  if (desc.terrain.enabled) {
    auto created = terrain::Terrain::create(terrain::settingsFromScene(desc.terrain));
    if (!created) return makeError(desc.path + ": /terrain: " + created.error().message);
    field.emplace(std::move(created).value());
  }
  std::map<std::string, LoadedModel> cache;
  for (size_t i = 0; i < desc.models.size(); ++i) {
    const ModelDesc& m = desc.models[i];
    const std::string where = desc.path + ": /models/" + std::to_string(i);
    auto it = cache.find(m.path);
    if (it == cache.end()) {
      auto model = loadGltf(m.path);
      if (!model) return makeError(where + "/path: " + model.error().message);
      auto animated = buildAnimatedModel(*model);
      if (!animated) return makeError(where + ": " + animated.error().message);
      LoadedModel loaded{std::move(model).value(), std::move(animated).value(), {}};
      addMaterials(loaded, *scene);
      it = cache.emplace(m.path, std::move(loaded)).first;
    }
    auto clip = findClip(it->second.animated, m.clip, m.path);
    if (!clip) return makeError(where + "/clip: " + clip.error().message);
    const double ground = m.onTerrain && field ? field->heightAt(m.position.x, m.position.z) : 0.0;
    if (auto s = addModelInstance(it->second, m, *clip, time, ground, *scene, stats); !s) {
      return makeError(where + ": " + s.error().message);
    }
  }
  if (field) {
    if (auto s = addTerrain(desc, *field, viewportHeight, *scene, stats); !s) return s.error();
  }
  stats.skinSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.bvhSeconds = scene->build();
  if (statsOut) *statsOut = stats;
  return scene;
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
