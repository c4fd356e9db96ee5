#pragma once
// Where every frame is drawn: an offscreen framebuffer with colour and depth,
// multisampled when asked and resolved into a single-sample colour texture. Drawing
// into our own FBO (never the default framebuffer) is what makes a frame
// byte-identical across OSMesa, EGL and a GLFW window.
#include "core/image.h"
#include "core/result.h"
#include "gl/resources.h"

namespace engine {

class RenderTarget {
 public:
  static Result<RenderTarget> create(int width, int height, int samples);
  // The most MSAA samples this GL offers (GL_MAX_SAMPLES).
  static int maxSamples();

  // Binds the (multisampled) framebuffer and sets the viewport.
  void bind() const;
  // Resolves multisampling into the single-sample texture; a no-op without MSAA.
  void resolve() const;
  // Reads the resolved colour back, top row first.
  Image readPixels() const;
  // Copies the resolved colour to the default framebuffer (window presentation).
  void blitToDefault(int windowWidth, int windowHeight) const;

  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const { return samples_; }

 private:
  int width_ = 0, height_ = 0, samples_ = 1;
  gl::Texture color_;            // single-sample, resolved result
  gl::Renderbuffer depth_;       // depth of the drawn framebuffer
  gl::Renderbuffer msaaColor_;   // only with samples > 1
  gl::Framebuffer draw_;         // what passes draw into
  gl::Framebuffer resolved_;     // only with samples > 1
};

}  // namespace engine
