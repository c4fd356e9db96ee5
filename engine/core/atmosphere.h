#pragma once
// The atmosphere of shaders/common/atmosphere.glsl compiled as C++: the CPU path
// tracer's air (raytrace/media.h) is the rasterizer's sky's, one text
// (tests/core/shading_texts_test.cpp compares the two compiles).
#include <cmath>

#include <glm/glm.hpp>

#include "asset/scene_desc.h"

namespace engine::atmospheretext {
// GLSL's built-ins and types, for the included text only.
using glm::abs;
using glm::exp;
using glm::max;
using glm::min;
using glm::pow;
using glm::sqrt;
using glm::vec3;

#define BRDF_INLINE inline
#include "common/atmosphere.glsl"
#undef BRDF_INLINE

// The scene's atmosphere as the text takes it.
inline Atmosphere atmosphereOf(const AtmosphereDesc& d) {
  Atmosphere a;
  a.bottomRadius = float(d.planetRadius);
  a.topRadius = float(d.planetRadius + d.thickness);
  a.rayleighScattering = d.rayleighScattering;
  a.rayleighScaleHeight = d.rayleighScaleHeight;
  a.mieScattering = d.mieScattering;
  a.mieAbsorption = d.mieAbsorption;
  a.mieScaleHeight = d.mieScaleHeight;
  a.mieAnisotropy = d.mieAnisotropy;
  a.ozoneAbsorption = d.ozoneAbsorption;
  a.ozoneCenter = d.ozoneCenter;
  a.ozoneHalfWidth = d.ozoneHalfWidth;
  a.groundAlbedo = d.groundAlbedo;
  return a;
}
}  // namespace engine::atmospheretext
