#pragma once
// The classic outdoor lighting every lit shader (lit.frag) takes: a sun, a
// hemispheric sky/ground ambient and distance fog toward the horizon colour.
#include <glm/glm.hpp>

#include "gl/shader.h"

namespace engine {

struct Lighting {
  glm::vec3 sunDirection{0.5f, 0.8f, 0.3f};  // toward the sun; normalised on use
  glm::vec3 sunColor{1.3f, 1.22f, 1.1f};
  glm::vec3 ambientSky{0.22f, 0.28f, 0.38f};
  glm::vec3 ambientGround{0.1f, 0.09f, 0.07f};
  glm::vec3 skyZenith{0.15f, 0.35f, 1.0f};
  glm::vec3 skyHorizon{0.6f, 0.7f, 0.85f};  // also the fog colour
  glm::vec3 skyGround{0.3f, 0.28f, 0.25f};
  float fogDensity = 0.02f;
  bool sunDisk = true;  // sky.frag draws the sun's disk
};

// Sets the lighting uniforms of lit.frag.
void setLightingUniforms(const gl::Program& program, const Lighting& lighting);
// Sets the uniforms of sky.frag.
void setSkyUniforms(const gl::Program& program, const Lighting& lighting);

}  // namespace engine
