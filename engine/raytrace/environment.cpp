#include "raytrace/environment.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>

#include "core/image.h"
#include "core/sky.h"

namespace engine::rt {
namespace latlong {
// GLSL's built-ins and types, for the included text only (as core/brdf.h does).
using glm::atan;
using glm::cos;
using glm::sin;
using glm::sqrt;
using glm::vec2;
using glm::vec3;

#include "common/latlong.glsl"
}  // namespace latlong

namespace {

// The gradient sky and the background are smooth (the sun disk aside, which a
// sampler takes from the sun light): a 512 x 256 table resolves them.
constexpr glm::ivec2 kAnalyticResolution{512, 256};

}  // namespace

Result<Environment> Environment::create(const SkyDesc& sky, std::optional<glm::vec3> sunDirection,
                                        std::shared_ptr<const FloatImage> image) {
  Environment env;
  env.sky_ = sky;
  if (!sky.enabled) return env;  // Constant: the background
  if (sky.image.empty()) {
    env.kind_ = Kind::Gradient;
    env.sun_ = sunDirection;
    return env;
  }
  if (!image) return makeError(sky.image + ": the sky's image was not decoded (scene/scene_images.h)");
  env.kind_ = Kind::Image;
  env.image_ = std::move(image);
  env.intensity_ = sky.intensity;
  const double radians = glm::radians(double(sky.rotationDegrees));
  env.cosRotation_ = float(std::cos(radians));
  env.sinRotation_ = float(std::sin(radians));
  return env;
}

glm::vec3 Environment::radiance(const glm::vec3& dir, bool sunDisk) const {
  switch (kind_) {
    case Kind::Constant:
      return sky_.background;
    case Kind::Gradient:
      return gradient(glm::normalize(dir), sunDisk);
    case Kind::Image:
      break;
  }
  // The image turned by the rotation shows at `dir` what it holds at `dir` turned back.
  const glm::vec3 local = latlong::rotateAboutY(dir, cosRotation_, -sinRotation_);
  return bilinear(uvOf(local)) * intensity_;
}

// The rasterizer's gradient sky (common/sky.glsl, core/sky.h), with its sun disk
// where one is asked for and the scene has a sun.
glm::vec3 Environment::gradient(const glm::vec3& d, bool sunDisk) const {
  const bool disk = sunDisk && sky_.sunDisk && sun_;
  return skytext::gradientSky(d, sky_.horizon, sky_.zenith, sky_.ground, disk ? glm::dot(d, *sun_) : 0.0f,
                              disk ? 1.0f : 0.0f);
}

// GL's GL_LINEAR between texel centres, repeating in u and clamped in v (the sky
// texture's wrap modes in the rasterizer).
glm::vec3 Environment::bilinear(glm::vec2 uv) const {
  const FloatImage& image = *image_;
  const float x = uv.x * float(image.width) - 0.5f, y = uv.y * float(image.height) - 0.5f;
  const float x0f = std::floor(x), y0f = std::floor(y);
  const float fx = x - x0f, fy = y - y0f;
  const int x0 = wrapTexel(int(x0f), image.width), x1 = wrapTexel(int(x0f) + 1, image.width);
  const int y0 = std::clamp(int(y0f), 0, image.height - 1), y1 = std::clamp(int(y0f) + 1, 0, image.height - 1);
  const glm::vec3 top = glm::mix(image.at(x0, y0), image.at(x1, y0), fx);
  const glm::vec3 bottom = glm::mix(image.at(x0, y1), image.at(x1, y1), fx);
  return glm::mix(top, bottom, fy);
}

glm::ivec2 Environment::resolution() const {
  return hasImage() ? glm::ivec2(image_->width, image_->height) : kAnalyticResolution;
}

glm::vec3 Environment::directionOf(glm::vec2 uv) { return latlong::latLongDirection(uv); }

glm::vec2 Environment::uvOf(const glm::vec3& dir) { return latlong::latLongUv(dir); }

}  // namespace engine::rt
