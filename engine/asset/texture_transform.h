#pragma once
// KHR_texture_transform's uv matrix: T * R * S applied to (u, v, 1), built once in
// C++ per material texture slot. The rasterizer passes the same matrix to
// common/material.glsl as a uniform and the tracers multiply by it on the CPU, so
// there is one definition of the transform.
//
// The rotation turns the uvs counter-clockwise in uv space (v pointing down the
// image), which is the image turned clockwise: u' = cos r u + sin r v,
// v' = -sin r u + cos r v. The extension's GLSL snippet reads this way when its
// mat3 is taken row by row; the Khronos Sample Viewer and three.js implement it so,
// and the spec's example (offset [0, 1], rotation pi/2, scale 0.5: the lower left
// quadrant turned 90 degrees clockwise) only comes out this way.
#include <cmath>

#include <glm/glm.hpp>

namespace engine {

inline glm::mat3 textureTransformMatrix(glm::vec2 offset, float rotation, glm::vec2 scale) {
  const float c = std::cos(rotation), s = std::sin(rotation);
  // glm is column-major: each vec3 below is a column.
  const glm::mat3 translation(glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(offset, 1));
  const glm::mat3 rotate(glm::vec3(c, -s, 0), glm::vec3(s, c, 0), glm::vec3(0, 0, 1));
  const glm::mat3 scaling(glm::vec3(scale.x, 0, 0), glm::vec3(0, scale.y, 0), glm::vec3(0, 0, 1));
  return translation * rotate * scaling;
}

// The matrix applied to one uv.
inline glm::vec2 transformUv(const glm::mat3& m, glm::vec2 uv) { return glm::vec2(m * glm::vec3(uv, 1.0f)); }

}  // namespace engine
