#include "render/transmission_pass.h"

#include <algorithm>
#include <cmath>

#include "gl/bindings.h"

namespace engine {

Status TransmissionPass::resize(int width, int height) {
  width_ = width;
  height_ = height;
  const int levels = 1 + int(std::floor(std::log2(double(std::max(width, height)))));
  source_ = gl::Texture::create2D(GL_RGBA16F, width, height, levels);
  source_.parameter(GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  source_.parameter(GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  source_.parameter(GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  source_.parameter(GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  fbo_ = gl::Framebuffer::create();
  fbo_.attach(GL_COLOR_ATTACHMENT0, source_);
  return fbo_.check("transmission-source");
}

void TransmissionPass::copy(const gl::Framebuffer& frame) {
  glBlitNamedFramebuffer(frame.id(), fbo_.id(), 0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                         GL_NEAREST);
  glGenerateTextureMipmap(source_.id());
}

void TransmissionPass::bind() const { source_.bind(gl::binding::kTransmissionSource); }

}  // namespace engine
