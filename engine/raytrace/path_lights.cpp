#include "raytrace/path_lights.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "raytrace/environment.h"
#include "scene/environment.h"

namespace engine::rt {
namespace {

float luminance(const glm::vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

PathLight pathLightOf(const LightDesc& l) {
  PathLight p;
  p.type = l.type;
  p.power = l.color * l.intensity;
  p.shadows = l.shadows;
  p.falloff = l.falloff;
  p.direction = glm::normalize(glm::vec3(l.direction));
  const LightCone cone = lightCone(l);
  p.cosOuter = cone.cosOuter;
  p.cosInner = cone.cosInner;
  if (l.type == LightType::Sun && l.angleDegrees > 0.0f) {
    const float half = glm::radians(l.angleDegrees) * 0.5f;
    p.cosMax = std::cos(half);
    // Irradiance at normal incidence, radiance * pi sin^2(half), equals a delta sun's pi I.
    p.radiance = p.power / (std::sin(half) * std::sin(half));
  }
  p.position = l.position;
  p.edgeU = l.edgeU;
  p.edgeV = l.edgeV;
  const glm::dvec3 c = glm::cross(l.edgeU, l.edgeV);
  p.area = float(glm::length(c));
  if (p.area > 0.0f) p.normal = glm::vec3(c / double(p.area));
  return p;
}

}  // namespace

EnvironmentLight::EnvironmentLight(RadianceFn radiance, glm::ivec2 resolution) : radiance_(std::move(radiance)) {
  const int w = std::max(1, resolution.x), h = std::max(1, resolution.y);
  std::vector<float> weights(std::size_t(w) * std::size_t(h));
  float total = 0.0f;
  for (int y = 0; y < h; ++y) {
    // sin(theta) is each cell's share of the sphere: the density is per uv, not per
    // solid angle, and pdf() divides it back out.
    const float sinTheta = std::sin(kPi * (float(y) + 0.5f) / float(h));
    for (int x = 0; x < w; ++x) {
      // The brightest of 2 x 2 points in the cell, so that a small bright spot
      // between cell centres still draws samples.
      float peak = 0.0f;
      for (int j = 0; j < 2; ++j) {
        for (int i = 0; i < 2; ++i) {
          const glm::vec2 uv((float(x) + 0.25f + 0.5f * float(i)) / float(w), (float(y) + 0.25f + 0.5f * float(j)) / float(h));
          peak = std::max(peak, luminance(radiance_(Environment::directionOf(uv))));
        }
      }
      weights[std::size_t(y) * std::size_t(w) + std::size_t(x)] = peak * sinTheta;
      total += peak;
    }
  }
  black_ = !(total > 0.0f);
  if (!black_) distribution_ = Distribution2D(weights, w, h);
}

glm::vec3 EnvironmentLight::sample(glm::vec2 u, float* pdf) const {
  *pdf = 0.0f;
  if (black_) return glm::vec3(0.0f, 1.0f, 0.0f);
  float uvPdf = 0.0f;
  const glm::vec2 uv = distribution_.sample(u, &uvPdf);
  const float sinTheta = std::sin(kPi * uv.y);
  if (sinTheta <= 0.0f) return glm::vec3(0.0f, 1.0f, 0.0f);
  *pdf = uvPdf / (2.0f * kPi * kPi * sinTheta);
  return Environment::directionOf(uv);
}

float EnvironmentLight::pdf(const glm::vec3& dir) const {
  if (black_) return 0.0f;
  const glm::vec2 uv = Environment::uvOf(dir);
  const float sinTheta = std::sin(kPi * uv.y);
  if (sinTheta <= 0.0f) return 0.0f;
  return distribution_.pdf(uv) / (2.0f * kPi * kPi * sinTheta);
}

std::shared_ptr<const PathLights> preparePathLights(const RtScene& scene) {
  auto lights = std::make_shared<PathLights>();
  for (const LightDesc& l : scene.lights()) {
    lights->lights.push_back(pathLightOf(l));
    if (lights->lights.back().type == LightType::Sun && lights->lights.back().cosMax < 1.0f) lights->coneSun = true;
  }
  // Without its sun disk: the sun is sampled as a light of its own. The scene outlives
  // the integrator that holds these.
  const Environment* environment = &scene.environment();
  lights->environment = EnvironmentLight([environment](const glm::vec3& d) { return environment->radiance(d, false); },
                                         environment->resolution());
  return lights;
}

}  // namespace engine::rt
