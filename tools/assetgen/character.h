#pragma once
// The generator's own description of a skinned, animated character, with no glTF in
// it: the robot builders fill it in and the glTF writer serialises it. Keeping the two
// apart lets the tests check the character's invariants (weights, loops) directly.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/image.h"
#include "core/keyframe.h"

namespace assetgen {

// Every joint's bind rotation is the identity, so its local bind translation is the
// difference of model-space positions and its inverse bind matrix a pure translation.
struct Joint {
  std::string name;
  int parent = -1;               // -1 for the root; parents come before children
  glm::vec3 bindPosition{0.0f};  // model space
};

struct Vertex {
  glm::vec3 position{0.0f};  // bind pose, model space
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
  glm::vec2 uv{0.0f};
  std::array<std::uint8_t, 4> joints{};  // unused slots are joint 0 with weight 0
  std::array<float, 4> weights{};        // sum exactly 1
};

struct Channel {
  int joint = 0;
  engine::AnimPath path = engine::AnimPath::Rotation;
  engine::Interpolation interpolation = engine::Interpolation::Linear;
  std::vector<float> times;
  // Rotation: quaternion x, y, z, w. Translation: x, y, z (w unused).
  // CubicSpline: three per key (in-tangent, value, out-tangent), tangents per second.
  std::vector<glm::vec4> values;
};

struct Clip {
  std::string name;
  float duration = 0.0f;
  std::vector<Channel> channels;
};

struct Character {
  std::string name;
  std::vector<Joint> joints;
  std::vector<Vertex> vertices;
  std::vector<std::uint16_t> indices;  // triangles, counter-clockwise seen from outside
  std::vector<Clip> clips;
  engine::Image albedo;  // RGBA8, the uv atlas of the material's base colour
};

}  // namespace assetgen
