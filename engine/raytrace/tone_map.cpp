#include "raytrace/tone_map.h"

#include <algorithm>
#include <cmath>

#include "core/srgb_curve.h"

namespace engine::rt {
glm::vec3 toneMap(glm::vec3 c, const RenderDesc& render) {
  c *= render.exposure;
  switch (render.toneMap) {
    case ToneMap::None:
      break;
    case ToneMap::Reinhard:
      c = c / (glm::vec3(1.0f) + c);
      break;
    case ToneMap::Aces:
      c = acesFit(c);
      break;
  }
  return c;
}

std::uint8_t encodeChannel(float v, OutputCurve curve) {
  // NaN fails every comparison; treat it as black rather than as undefined.
  if (!(v > 0.0f)) v = 0.0f;
  v = std::min(v, 1.0f);
  // The rasterizer's sRGB bytes (core/srgb_curve.h).
  if (curve != OutputCurve::Gamma22) return srgbByte(v);
  return std::uint8_t(int(std::pow(v, 1.0f / 2.2f) * 255.0f + 0.5f));
}

Image toImage(const Framebuffer& framebuffer, const RenderDesc& render) {
  Image image(framebuffer.width, framebuffer.height);
  for (int y = 0; y < framebuffer.height; ++y) {
    for (int x = 0; x < framebuffer.width; ++x) {
      const glm::vec3 c = toneMap(framebuffer.at(x, y), render);
      std::uint8_t* px = image.at(x, y);
      px[0] = encodeChannel(c.r, render.output);
      px[1] = encodeChannel(c.g, render.output);
      px[2] = encodeChannel(c.b, render.output);
      px[3] = 255;
    }
  }
  return image;
}

FloatImage toFloatImage(const Framebuffer& framebuffer) {
  FloatImage image;
  image.width = framebuffer.width;
  image.height = framebuffer.height;
  image.rgb.reserve(framebuffer.pixels.size() * 3);
  for (const glm::vec3& c : framebuffer.pixels) image.rgb.insert(image.rgb.end(), {c.r, c.g, c.b});
  return image;
}

}  // namespace engine::rt
