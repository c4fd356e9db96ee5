#include "render/render_target.h"

#include <string>

namespace engine {

int RenderTarget::maxSamples() {
  GLint samples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &samples);
  return samples;
}

Result<RenderTarget> RenderTarget::create(int width, int height, int samples) {
  const int most = maxSamples();
  if (samples < 1 || samples > most) {
    return makeError("msaa: " + std::to_string(samples) + " samples asked, this GL offers 1.." + std::to_string(most));
  }
  RenderTarget t;
  t.width_ = width;
  t.height_ = height;
  t.samples_ = samples;
  // sRGB storage: shaders write linear colour, the hardware encodes, and the bytes
  // read back are what a PNG viewer expects.
  t.color_ = gl::Texture::create2D(GL_SRGB8_ALPHA8, width, height, 1);
  t.depth_ = gl::Renderbuffer::create(GL_DEPTH_COMPONENT32F, width, height, samples);
  t.draw_ = gl::Framebuffer::create();
  if (samples > 1) {
    t.msaaColor_ = gl::Renderbuffer::create(GL_SRGB8_ALPHA8, width, height, samples);
    t.draw_.attach(GL_COLOR_ATTACHMENT0, t.msaaColor_);
    t.resolved_ = gl::Framebuffer::create();
    t.resolved_.attach(GL_COLOR_ATTACHMENT0, t.color_);
  } else {
    t.draw_.attach(GL_COLOR_ATTACHMENT0, t.color_);
  }
  t.draw_.attach(GL_DEPTH_ATTACHMENT, t.depth_);
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (auto s = t.draw_.check("target " + size); !s) return s.error();
  if (samples > 1) {
    if (auto s = t.resolved_.check("target-resolve " + size); !s) return s.error();
  }
  return t;
}

void RenderTarget::bind() const {
  draw_.bind();
  glViewport(0, 0, width_, height_);
  // Shaders write linear colour; the sRGB attachment encodes it on write.
  glEnable(GL_FRAMEBUFFER_SRGB);
}

void RenderTarget::resolve() const {
  if (samples_ <= 1) return;
  glBlitNamedFramebuffer(draw_.id(), resolved_.id(), 0, 0, width_, height_, 0, 0, width_, height_,
                         GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

Image RenderTarget::readPixels() const {
  Image image(width_, height_);
  const GLuint source = samples_ > 1 ? resolved_.id() : draw_.id();
  glBindFramebuffer(GL_READ_FRAMEBUFFER, source);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  flipVertically(image);
  return image;
}

void RenderTarget::blitToDefault(int windowWidth, int windowHeight) const {
  const GLuint source = samples_ > 1 ? resolved_.id() : draw_.id();
  // Copy the encoded bytes as they are: with GL_FRAMEBUFFER_SRGB on, the blit would
  // decode the sRGB source to linear and the window would show it too dark.
  glDisable(GL_FRAMEBUFFER_SRGB);
  glBlitNamedFramebuffer(source, 0, 0, 0, width_, height_, 0, 0, windowWidth, windowHeight,
                         GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

}  // namespace engine
