#pragma once
// Where the frame goes. The world is drawn into the frame's target: an HDR image
// (multisampled and/or supersampled as the render settings say), which the post
// pass tone maps into the framebuffer the caller bound; or, with direct output
// (needsNoHdrTarget in scene_renderer_setup.cpp), the display values the fragment
// shaders write themselves (common/output.glsl), into an RGBA8 target copied out
// as it is, into the caller's own colour image, or straight into the caller's
// framebuffer. Not part of the engine's interface.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "asset/scene_desc.h"
#include "core/linear_image.h"
#include "core/result.h"
#include "gl/resources.h"
#include "gl/shader.h"

namespace engine {

struct SceneStats;

// What the fragment shaders of a direct-output scene are built with
// (common/output.glsl): exposure, the tone map and the curve.
std::vector<std::string> displayDefines(const RenderDesc& render);

class OutputPass {
 public:
  // `direct`: direct output (no HDR target, no post pass).
  static Result<std::unique_ptr<OutputPass>> create(const std::string& shaderDir, const RenderDesc& render,
                                                    bool direct, SceneStats* stats);
  bool direct() const { return direct_; }

  // Adds the deferred passes' images to the target's framebuffer of width x height
  // (and sizes what copies it) when the target is made anew.
  using AttachImages = std::function<Status(gl::Framebuffer& target, int width, int height)>;
  // A frame of width x height pixels into the framebuffer bound now. `deferred`:
  // some pass keeps images beside the frame's depth (which then needs a target of
  // its own); `depthFormat`: the target's depth (with a stencil for deferred
  // surfaces).
  Status begin(int width, int height, bool deferred, GLenum depthFormat, const AttachImages& attach);
  // The frame's image size (supersampled) and framebuffer.
  int width() const { return targetWidth_; }
  int height() const { return targetHeight_; }
  const gl::Framebuffer& framebuffer() const { return drawFbo_; }
  // Binds the framebuffer the world is drawn into and clears it to `background`
  // (linear radiance), far depth and stencil 0, in the opaque pass's state.
  void bindCleared(const glm::vec3& background, bool leftHanded);
  // The world drawn: into the caller's framebuffer, tone mapped (the post pass),
  // copied, or nothing more where it was drawn there.
  void finish();
  // The last frame's linear radiance as drawn, before exposure, tone map and curve:
  // the HDR target read back (RGBA16F: the half floats the post pass reads, exact
  // as float) at the caller's size, top row first. A supersampled pixel is the mean
  // of its N x N samples, as light adds (the post pass averages after the tone map).
  // An error under direct output, which has no HDR target.
  Result<FloatImage> readLinear() const;
  std::string describe() const;

 private:
  OutputPass(const RenderDesc& render, bool direct, SceneStats* stats)
      : render_(render), direct_(direct), stats_(stats) {}
  Status makeTarget(int width, int height, GLenum depthFormat, const AttachImages& attach);
  bool useColourOf(const gl::FramebufferLayout* caller);

  RenderDesc render_;
  bool direct_;
  SceneStats* stats_;
  // The one post variant these settings need (post.frag says why not uniforms).
  gl::Program post_;
  // The display curve's table (core/srgb_curve.h) for every program that writes
  // display values; none under the gamma 2.2 curve.
  gl::Buffer displayTableTexels_;
  gl::Texture displayTable_;
  gl::VertexArray emptyVao_ = gl::VertexArray::create();
  int targetWidth_ = 0, targetHeight_ = 0;
  gl::Texture hdr_;
  gl::Renderbuffer msaaColor_, depth_;
  gl::Framebuffer drawFbo_, resolveFbo_;
  // The caller's colour image attached to drawFbo_ in hdr_'s place last frame
  // (useColourOf), or 0.
  GLuint borrowedColour_ = 0;
  // This frame's: the caller's framebuffer and size; the world drawn straight into
  // it, or into drawFbo_ with the caller's colour image.
  GLuint caller_ = 0;
  int callerWidth_ = 0, callerHeight_ = 0;
  bool intoCaller_ = false, borrowed_ = false;
};

}  // namespace engine
