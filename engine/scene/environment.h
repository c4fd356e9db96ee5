#pragma once
// What lights a scene, as every renderer takes it (GL-free): the lights, the scene
// file's followed by each model instance's KHR_lights_punctual, and the sky, its
// gradient or its image decoded once (scene/scene_images.h). The rasterizer's frame
// block and sky pass (render/frame_uniforms.h, sky_pass.h) and the tracers' scene
// (RtScene::fromSceneDesc) read this, not the scene file's lights, so a model that
// brings its own lamp lights both renderers' images alike.
//
// Engine units, one for every renderer: a sun of colour c and intensity I gives a
// surface facing it the irradiance c I; a point light gives c I / d^2 at distance d
// with falloff, c I everywhere without it (the course's), and a spot the same within
// its inner cone, fading to none at its outer cone; an area light emits the
// radiance c I from each point of its front face; the sky's colours, and its image
// times its intensity, are radiance. glTF's lux (directional) and candela (point,
// spot) are taken as they are: 1 lux is one sun unit, 1 cd one point unit
// (asset/model_lights.h says why).
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "asset/model_data.h"
#include "asset/scene_desc.h"
#include "core/linear_image.h"

namespace engine {

// The first light of type Sun in `lights`, or null; and its unit direction toward it.
// The sun of a scene (SceneEnvironment::sun) and of a tracer's scene
// (RtScene::sunDirection) alike.
const LightDesc* firstSun(std::span<const LightDesc> lights);
std::optional<glm::vec3> sunDirectionOf(std::span<const LightDesc> lights);

// A light's cone as every renderer weighs its light (common/spot_cone.glsl's
// spotAttenuation, with the cosine between `axisToLight` and the direction toward the
// light): a spot's axis turned toward it and the cosines of its half-angles; for
// every other light a cone that holds every direction, whose weight is exactly 1.
struct LightCone {
  glm::vec3 axisToLight{0.0f, 1.0f, 0.0f};
  float cosOuter = -3.0f, cosInner = -2.0f;
};
LightCone lightCone(const LightDesc& light);

struct SceneEnvironment {
  std::vector<LightDesc> lights;
  SkyDesc sky;
  std::shared_ptr<const FloatImage> skyImage;  // null without an image sky

  // The scene file's lights and sky; `skyImage` is its sky's image, decoded.
  static SceneEnvironment of(const SceneDesc& desc, std::shared_ptr<const FloatImage> skyImage);
  // Adds a model's KHR_lights_punctual lights, placed by its nodes in the rest pose
  // under `world` (the instance's root): they do not follow its animation.
  void addModelLights(const ModelData& model, const glm::dmat4& world);

  // The sun: the first light of type Sun, or null. The gradient sky draws its disk
  // toward it; the rasterizer gives it the shadow map (its other lights are
  // unshadowed, frame_uniforms.h).
  const LightDesc* sun() const;
  std::optional<glm::vec3> sunDirection() const;
};

}  // namespace engine
