#pragma once
// The per-frame uniform block of shaders/common/frame.glsl (std140: vec4-aligned
// members), bound at binding 0 for every scene program, the terrain's included.
#include <glm/glm.hpp>

namespace engine {

inline constexpr int kMaxPointLights = 8;  // MAX_POINT_LIGHTS in frame.glsl
inline constexpr unsigned kFrameBlockBinding = 0;

struct FrameBlock {
  glm::mat4 viewProjection{1.0f};
  glm::mat4 sunShadowMatrix{1.0f};
  glm::vec4 sunDirection{0.0f};
  glm::vec4 sunColor{0.0f};
  glm::vec4 pointPosition[kMaxPointLights]{};
  glm::vec4 pointColor[kMaxPointLights]{};
  glm::vec4 ambientSky{0.0f};
  glm::vec4 ambientGround{0.0f};
  glm::vec4 fog{0.0f};
  glm::vec4 shadowParams{0.0f};
  glm::ivec4 counts{0};
  glm::mat4 sunShadowMatrixFar{1.0f};
  glm::vec4 sunFarParams{0.0f};
  glm::vec4 shIrradiance[9]{};  // rgb: the environment's SH irradiance (render/ibl.h)
  glm::vec4 iblParams{0.0f};    // x: the prefiltered chain's last level (roughness 1)
};

}  // namespace engine
