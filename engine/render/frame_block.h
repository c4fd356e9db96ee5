#pragma once
// The per-frame uniform block: shaders/common/frame.glsl's text, compiled as C++ (its
// block becomes the struct the renderer fills and uploads), bound at binding 0 for
// every scene program, the terrain's included. tests/render/frame_block_test.cpp
// holds the GL's std140 offsets against this struct's.
#include <glm/glm.hpp>

namespace engine {
namespace frametext {
using glm::ivec4;
using glm::mat4;
using glm::vec4;
// `layout(std140, binding = BLOCK_FRAME) uniform Frame {...};` reads as
// `struct Frame {...};`.
#define layout(...)
#define uniform struct
#include "common/frame.glsl"
#undef uniform
#undef layout
}  // namespace frametext

inline constexpr int kMaxPointLights = MAX_POINT_LIGHTS;
#undef MAX_POINT_LIGHTS
inline constexpr unsigned kFrameBlockBinding = 0;

// The text's block, its matrices the identity and the rest zero until filled.
struct FrameBlock : frametext::Frame {
  FrameBlock() : frametext::Frame{} {
    u_viewProjection = glm::mat4(1.0f);
    u_sunShadowMatrix = glm::mat4(1.0f);
    u_sunShadowMatrixFar = glm::mat4(1.0f);
  }
};
static_assert(sizeof(FrameBlock) == sizeof(frametext::Frame));

}  // namespace engine
