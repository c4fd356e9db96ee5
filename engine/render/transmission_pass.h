#pragma once
// What transmissive materials (KHR_materials_transmission) refract
// (common/transmission.glsl): the main view's colour before them (sky, terrain
// and opaque draws; MSAA resolved by the copy), with its mip chain for rough
// surfaces. Probe views refract the camera's last copy. Not part of the engine's
// interface.
#include "core/result.h"
#include "gl/resources.h"

namespace engine {

class TransmissionPass {
 public:
  // A copy of width x height, the frame target's.
  Status resize(int width, int height);
  // The view's colour so far, from `frame`'s framebuffer.
  void copy(const gl::Framebuffer& frame);
  // For the transmissive draws.
  void bind() const;

 private:
  int width_ = 0, height_ = 0;
  gl::Texture source_;
  gl::Framebuffer fbo_;
};

}  // namespace engine
