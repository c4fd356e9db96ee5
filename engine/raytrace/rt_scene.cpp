#include "raytrace/rt_scene.h"

#include "scene/materials.h"
#include "scene/shapes.h"

#include <cassert>
#include <string>
#include <utility>

namespace engine::rt {
namespace {

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

}  // namespace

RtScene::RtScene() { rebuildGradientSky(); }

std::optional<glm::vec3> RtScene::sunDirection() const { return sunDirectionOf(lights_); }

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
  return fromSceneDesc(desc, sceneFileMaterials(desc, images), SceneEnvironment::of(desc, images.sky));
}

Result<RtScene> RtScene::fromSceneDesc(const SceneDesc& desc, std::span<const SceneMaterial> materials,
                                       const SceneEnvironment& environment) {
  if (materials.size() != desc.materials.size()) return makeError(desc.path + ": the material table is another scene's");
  RtScene scene;
  // The file's materials as they are: the table's constructor leaves what addMaterial
  // works out of a glTF material's layers at its defaults, as it always has.
  std::vector<MaterialDesc> surfaces;
  for (const SceneMaterial& m : materials) surfaces.push_back(m.surface);
  if (!surfaces.empty()) scene.materialTable_ = RtMaterials(std::move(surfaces));
  for (size_t i = 0; i < materials.size(); ++i) {
    if (auto s = scene.materialTable_.setSceneMaterial(int(i), materials[i]); !s) return s.error();
  }
  scene.camera_ = desc.camera;
  scene.lights_ = environment.lights;
  scene.sky_ = environment.sky;
  auto sky = Environment::create(environment.sky, scene.sunDirection(), environment.skyImage);
  if (!sky) return makeError(desc.path + ": /sky/image: " + sky.error().message);
  scene.environment_ = std::move(sky).value();
  scene.ambientSky_ = ambientSkyColor(desc);
  scene.ambientGround_ = ambientGroundColor(desc);
  scene.render_ = desc.render;
  scene.fog_ = desc.fog;
  scene.atmosphere_ = desc.atmosphere;
  scene.media_ = desc.media;
  const int materialCount = int(scene.materials().size());
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
        auto id = scene.addMesh(boxMesh(p, p.material, scene.materials()[size_t(p.material)].textureScale));
        if (!id) return id.error();
        break;
      }
    }
  }
  scene.build();
  return scene;
}

template <typename T>
float RtScene::transmittance(const Ray<T>& shadowRay, const Vec3<T>* target, std::uint64_t& rays) const {
  ++rays;
  if (!hasTransparency()) return intersectAny(shadowRay) ? 0.0f : 1.0f;
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

}  // namespace engine::rt
