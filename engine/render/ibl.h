#pragma once
// Image-based lighting: the rasterizer's shortcut of the path tracer's environment
// light. From a cube map of the environment's radiance (drawn once at scene load,
// without the sun disk: the path tracer's view of it), the split-sum (Karis 2013)
// needs a GGX-prefiltered mip chain (one roughness per level, shaders/
// ibl_prefilter.comp) and a BRDF table (core/ibl_tables.h, on the CPU from
// brdf.glsl); the diffuse takes order-2 SH irradiance (Ramamoorthi-Hanrahan 2001).
// Ambient::Sh builds only the table and the SH, and keeps no cube map.
#include <string>

#include "asset/scene_desc.h"
#include "core/ibl_tables.h"
#include "core/result.h"
#include "gl/resources.h"

namespace engine {

class EnvironmentLighting {
 public:
  // `environment`: an RGBA16F cube map with its full mip chain filled, `size` texels
  // a side. Needs a current context.
  static Result<EnvironmentLighting> create(const std::string& shaderDir, const gl::Texture& environment, int size,
                                            Ambient ambient);

  // Binds the table (and the prefiltered cube) to their units.
  void bind() const;
  const ShIrradiance& sh() const { return sh_; }
  // The prefiltered chain's last level (roughness 1); 0 without one.
  int maxLevel() const { return levels_ - 1; }
  const gl::Texture& prefiltered() const { return prefiltered_; }
  // "brdf-lut(32x32) sh9(from cube 128) prefiltered(cube 128, 5 levels 128..8, 128
  // ggx samples)", for demo --describe.
  std::string describe() const;

 private:
  Status prefilter(const std::string& shaderDir, const gl::Texture& environment, int size);

  gl::Texture splitSum_, prefiltered_;
  ShIrradiance sh_;
  int size_ = 0, levels_ = 0;
};

// The GL cube map of `size` texels a side, RGBA16F, with `levels` mip levels (0: the
// full chain), trilinear and seamless.
gl::Texture makeCubeMap(int size, int levels);

}  // namespace engine
