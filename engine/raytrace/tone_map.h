#pragma once
// From the linear framebuffer to 8 bits: exposure, tone map, clamp to [0, 1], output
// curve (sRGB, or gamma 1/2.2 as the course), then (int)(v * 255 + 0.5). Alpha is 255.
// Or to float, as it is.
#include "asset/scene_desc.h"
#include "core/image.h"
#include "core/linear_image.h"
#include "raytrace/render_types.h"

namespace engine::rt {

glm::vec3 toneMap(glm::vec3 linear, const RenderDesc& render);
// One linear channel in [0, 1] to its 8-bit code through the output curve.
std::uint8_t encodeChannel(float v, OutputCurve curve);
Image toImage(const Framebuffer& framebuffer, const RenderDesc& render);
// The framebuffer as it is, before exposure, tone map and curve: what a float
// screenshot (core/float_image_io.h) writes.
FloatImage toFloatImage(const Framebuffer& framebuffer);

}  // namespace engine::rt
