#pragma once
// The environment as an infinite light: what a ray that leaves the scene sees. One
// of three, from the scene's sky: the background colour (sky disabled), the sky's
// gradient with its sun disk (as shaders/sky.frag draws it), or a lat-long image
// (a Radiance .hdr or a PNG) times an intensity, turned about +y. The lat-long
// convention is shaders/common/latlong.glsl's, which sky.frag samples with too.
#include <memory>
#include <optional>

#include <glm/glm.hpp>

#include "asset/scene_desc.h"
#include "core/linear_image.h"
#include "core/result.h"

namespace engine::rt {

class Environment {
 public:
  Environment() = default;  // black everywhere
  // The sky of a scene; sunDirection (unit, toward the sun) draws the gradient sky's
  // sun disk when sky.sunDisk. An image sky (sky.image set) samples `image`, decoded
  // by the scene layer (scene/scene_images.h): without it, an error. An image has no
  // sun disk of its own making: its sun is in its pixels.
  static Result<Environment> create(const SkyDesc& sky, std::optional<glm::vec3> sunDirection,
                                    std::shared_ptr<const FloatImage> image = nullptr);

  // Radiance arriving from unit direction `dir` (pointing away from the scene).
  // sunDisk = false leaves the gradient sky's sun disk out (a path tracer that samples
  // the sun as a light must not count it twice).
  glm::vec3 radiance(const glm::vec3& dir, bool sunDisk = true) const;
  // The lat-long grid a sampler should tabulate the environment on: the image's
  // size, or 512 x 256 for the gradient sky / background.
  glm::ivec2 resolution() const;
  bool hasImage() const { return kind_ == Kind::Image; }
  bool isConstant() const { return kind_ == Kind::Constant; }  // background colour only
  // An image sky as radiance() samples it (the GPU tracer copies it): the image (null
  // for the others), its intensity and its turn about +y (cosine, sine).
  const FloatImage* image() const { return image_.get(); }
  float intensity() const { return intensity_; }
  glm::vec2 rotation() const { return {cosRotation_, sinRotation_}; }

  // The one lat-long convention, both ways (common/latlong.glsl; the image's rotation
  // is applied inside radiance(), not here): u in [0, 1) about +y, u = 0.5 toward +z,
  // 0.75 toward -x, 0 toward -z (the seam), 0.25 toward +x; v in [0, 1], v = 0 at +y
  // (the zenith, the image's top row), 1 at -y. uvOf takes any non-zero length;
  // straight up or down u is 0.5.
  static glm::vec3 directionOf(glm::vec2 uv);
  static glm::vec2 uvOf(const glm::vec3& dir);

 private:
  enum class Kind { Constant, Gradient, Image };
  glm::vec3 gradient(const glm::vec3& d, bool sunDisk) const;
  glm::vec3 bilinear(glm::vec2 uv) const;

  Kind kind_ = Kind::Constant;
  SkyDesc sky_;  // the gradient's colours, the background
  std::optional<glm::vec3> sun_;
  // Shared: scenes and their copies hold one decoded image (up to 384 MiB).
  std::shared_ptr<const FloatImage> image_;
  float intensity_ = 1.0f;
  // The image's turn about +y; radiance() turns directions back by it.
  float cosRotation_ = 1.0f, sinRotation_ = 0.0f;
};

}  // namespace engine::rt
