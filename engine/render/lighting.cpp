#include "render/lighting.h"

namespace engine {

void setLightingUniforms(const gl::Program& program, const Lighting& l) {
  program.set("u_sunDirection", glm::normalize(l.sunDirection));
  program.set("u_sunColor", l.sunColor);
  program.set("u_skyColor", l.ambientSky);
  program.set("u_groundColor", l.ambientGround);
  program.set("u_fogColor", l.skyHorizon);
  program.set("u_fogDensity", l.fogDensity);
}

void setSkyUniforms(const gl::Program& program, const Lighting& l) {
  program.set("u_sunDirection", glm::normalize(l.sunDirection));
  program.set("u_skyColor", l.skyZenith);
  program.set("u_horizonColor", l.skyHorizon);
  program.set("u_groundColor", l.skyGround);
  program.set("u_sunDisk", l.sunDisk ? 1.0f : 0.0f);
}

}  // namespace engine
