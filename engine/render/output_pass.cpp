#include "render/output_pass.h"

#include <cstdio>

#include "core/srgb_curve.h"
#include "gl/bindings.h"
#include "render/pass_state.h"
#include "render/scene_stats.h"

namespace engine {
namespace {

// common/output.glsl's targetColor under DIRECT_OUTPUT on the CPU (the direct path's
// clear colour): exposure, the tone map, then the curve.
glm::vec3 displayValue(glm::vec3 c, const RenderDesc& render) {
  c *= render.exposure;
  if (render.toneMap == ToneMap::Aces && render.output != OutputCurve::Gamma22)
    return glm::vec3(acesSrgbByte(c.r), acesSrgbByte(c.g), acesSrgbByte(c.b)) / 255.0f;
  if (render.toneMap == ToneMap::Reinhard) c = c / (1.0f + c);
  if (render.toneMap == ToneMap::Aces) c = acesFit(c);
  c = glm::clamp(c, 0.0f, 1.0f);
  if (render.output == OutputCurve::Gamma22) return glm::pow(c, glm::vec3(1.0f / 2.2f));
  return glm::vec3(srgbByte(c.r), srgbByte(c.g), srgbByte(c.b)) / 255.0f;
}

// The direct path draws into the caller's framebuffer itself, with no target of its
// own and no copy, when that is a single-sample framebuffer object of the frame's
// size with 8-bit normalised colour (RGBA8 or SRGB8_ALPHA8: with GL_FRAMEBUFFER_SRGB
// off both store the shader's bytes as they are) and 32-bit float depth (the
// reverse-Z depth every pass tests against; fixed-point depth would move bytes).
// On llvmpipe the copy was a shader pass over every pixel: about 3 ms at 1280x720.
bool takesDirectFrame(const gl::FramebufferLayout& l, int width, int height) {
  const bool color8 = l.colorType == GL_UNSIGNED_NORMALIZED && l.colorBits[0] == 8 && l.colorBits[1] == 8 &&
                      l.colorBits[2] == 8 && l.colorBits[3] == 8;
  return l.samples == 0 && l.width == width && l.height == height && color8 && l.depthBits == 32 &&
         l.depthType == GL_FLOAT;
}

// The HDR target's texels (RGBA, bottom row first, `samples` x `samples` a pixel) as
// the frame's pixels (RGB, top row first), each the mean of its samples.
FloatImage framePixels(const std::vector<float>& rgba, int width, int height, int samples) {
  FloatImage image;
  image.width = width / samples;
  image.height = height / samples;
  image.rgb.assign(std::size_t(image.width) * std::size_t(image.height) * 3, 0.0f);
  const float weight = 1.0f / float(samples * samples);  // 1 without supersampling: the texels as they are
  for (int y = 0; y < image.height; ++y) {
    const int below = (image.height - 1 - y) * samples;
    for (int x = 0; x < image.width; ++x) {
      float* out = &image.rgb[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 3];
      for (int sy = 0; sy < samples; ++sy) {
        for (int sx = 0; sx < samples; ++sx) {
          const float* texel = &rgba[(std::size_t(below + sy) * std::size_t(width) + std::size_t(x * samples + sx)) * 4];
          for (int c = 0; c < 3; ++c) out[c] += texel[c];
        }
      }
      for (int c = 0; c < 3; ++c) out[c] *= weight;
    }
  }
  return image;
}

}  // namespace

std::vector<std::string> displayDefines(const RenderDesc& render) {
  char exposure[32];
  std::snprintf(exposure, sizeof(exposure), "EXPOSURE %.9g", double(render.exposure));  // the float's exact value
  std::vector<std::string> defines{"DIRECT_OUTPUT 1", "TONE_MAP " + std::to_string(int(render.toneMap)), exposure};
  if (render.output == OutputCurve::Gamma22) defines.push_back("OUTPUT_GAMMA22 1");
  return defines;
}

Result<std::unique_ptr<OutputPass>> OutputPass::create(const std::string& shaderDir, const RenderDesc& render,
                                                       bool direct, SceneStats* stats) {
  std::unique_ptr<OutputPass> pass(new OutputPass(render, direct, stats));
  if (render.output != OutputCurve::Gamma22) {
    // The table common/output.glsl reads: ACES and the curve in one where the
    // fragment shaders write display values after ACES (its targetColor), else the
    // curve's.
    const DisplayTable& table = direct && render.toneMap == ToneMap::Aces ? acesSrgbTable() : srgbTable();
    pass->displayTableTexels_ = gl::Buffer::create(table.texels.size() * sizeof(float), table.texels.data(), 0);
    pass->displayTable_ = gl::Texture::ofBuffer(pass->displayTableTexels_, GL_RG32F);
  }
  if (direct) return pass;
  std::vector<std::string> defines{"SUPERSAMPLE " + std::to_string(render.supersample),
                                   "TONE_MAP " + std::to_string(int(render.toneMap))};
  if (render.output == OutputCurve::Gamma22) defines.push_back("OUTPUT_GAMMA22 1");
  auto program = gl::Program::build(shaderDir, {{GL_VERTEX_SHADER, "post.vert"}, {GL_FRAGMENT_SHADER, "post.frag"}}, defines);
  if (!program) return program.error();
  pass->post_ = std::move(program).value();
  return pass;
}

Status OutputPass::makeTarget(int width, int height, GLenum depthFormat, const AttachImages& attach) {
  const int w = width * render_.supersample, h = height * render_.supersample;
  if (w == targetWidth_ && h == targetHeight_ && drawFbo_) return Ok{};
  targetWidth_ = w;
  targetHeight_ = h;
  hdr_ = gl::Texture::create2D(direct_ ? GL_RGBA8 : GL_RGBA16F, w, h, 1);
  hdr_.parameter(GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  hdr_.parameter(GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  const int samples = render_.msaa > 1 ? render_.msaa : 0;
  depth_ = gl::Renderbuffer::create(depthFormat, w, h, samples);
  drawFbo_ = gl::Framebuffer::create();
  borrowedColour_ = 0;
  if (samples > 0) {
    msaaColor_ = gl::Renderbuffer::create(GL_RGBA16F, w, h, samples);
    drawFbo_.attach(GL_COLOR_ATTACHMENT0, msaaColor_);
    resolveFbo_ = gl::Framebuffer::create();
    resolveFbo_.attach(GL_COLOR_ATTACHMENT0, hdr_);
  } else {
    drawFbo_.attach(GL_COLOR_ATTACHMENT0, hdr_);
  }
  drawFbo_.attach(depthFormat == GL_DEPTH32F_STENCIL8 ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT, depth_);
  if (auto s = attach(drawFbo_, w, h); !s) return s;
  if (auto s = drawFbo_.check(direct_ ? "scene-display" : "scene-hdr"); !s) return s;
  return samples > 0 ? resolveFbo_.check("scene-hdr-resolve") : Status(Ok{});
}

// The direct path's colour image in drawFbo_: the caller's (`caller`, when it can
// be attached elsewhere), else drawFbo_'s own. True when the caller's is attached.
// Attached anew every frame: a caller's resized target may be a new image under
// the name of the one it deleted.
bool OutputPass::useColourOf(const gl::FramebufferLayout* caller) {
  const GLuint wanted = caller && caller->colorObjectType != GL_NONE ? caller->colorObject : 0;
  if (wanted == 0) {
    if (borrowedColour_ != 0) drawFbo_.attach(GL_COLOR_ATTACHMENT0, hdr_);
  } else if (caller->colorObjectType == GL_RENDERBUFFER) {
    glNamedFramebufferRenderbuffer(drawFbo_.id(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, wanted);
  } else {
    glNamedFramebufferTexture(drawFbo_.id(), GL_COLOR_ATTACHMENT0, wanted, caller->colorLevel);
  }
  borrowedColour_ = wanted;
  return wanted != 0;
}

Status OutputPass::begin(int width, int height, bool deferred, GLenum depthFormat, const AttachImages& attach) {
  GLint callerFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &callerFramebuffer);
  caller_ = GLuint(callerFramebuffer);
  callerWidth_ = width;
  callerHeight_ = height;
  const gl::FramebufferLayout callerLayout = gl::framebufferLayout(caller_);
  const bool direct = direct_ && takesDirectFrame(callerLayout, width, height);
  // Deferred surfaces need their targets (and stencil) beside the frame's depth:
  // drawFbo_ then borrows the caller's colour image where it can, so nothing is copied.
  intoCaller_ = direct && !deferred;
  if (intoCaller_) {
    targetWidth_ = width;
    targetHeight_ = height;
  } else if (auto status = makeTarget(width, height, depthFormat, attach); !status) {
    return status;
  }
  borrowed_ = direct_ && !intoCaller_ && useColourOf(direct ? &callerLayout : nullptr);
  if (displayTable_) displayTable_.bind(gl::binding::kDisplayTable);
  return Ok{};
}

void OutputPass::bindCleared(const glm::vec3& background, bool leftHanded) {
  glBindFramebuffer(GL_FRAMEBUFFER, intoCaller_ ? caller_ : drawFbo_.id());
  glViewport(0, 0, targetWidth_, targetHeight_);
  glDisable(GL_FRAMEBUFFER_SRGB);
  applyPassState(opaquePassFor(leftHanded));  // depth writes on, for the clear
  const glm::vec3 clear = direct_ ? displayValue(background, render_) : background;
  glClearColor(clear.r, clear.g, clear.b, 1.0f);
  glClearDepth(0.0);  // reverse-Z: far is 0
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
}

void OutputPass::finish() {
  if (direct_) {
    // Display values already: drawn into the caller's framebuffer, or copied into it
    // as they are.
    glClearDepth(1.0);
    glBindFramebuffer(GL_FRAMEBUFFER, caller_);
    glViewport(0, 0, callerWidth_, callerHeight_);
    if (!intoCaller_ && !borrowed_) {
      stats_->frameCopies = 1;
      glBlitNamedFramebuffer(drawFbo_.id(), caller_, 0, 0, targetWidth_, targetHeight_, 0, 0, callerWidth_,
                             callerHeight_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    return;
  }
  if (render_.msaa > 1) {
    glBlitNamedFramebuffer(drawFbo_.id(), resolveFbo_.id(), 0, 0, targetWidth_, targetHeight_, 0, 0, targetWidth_,
                           targetHeight_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }
  // Post: into the framebuffer the caller bound. It receives display values, so
  // sRGB encoding on write is off (the shader applies the output curve itself).
  applyPassState(kPostPass);
  stats_->frameCopies = 1;
  glClearDepth(1.0);
  glBindFramebuffer(GL_FRAMEBUFFER, caller_);
  glViewport(0, 0, callerWidth_, callerHeight_);
  glDisable(GL_FRAMEBUFFER_SRGB);
  post_.use();
  post_.set("u_exposure", render_.exposure);
  hdr_.bind(gl::binding::kHdr);
  emptyVao_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  stats_->drawCalls += 1;
}

Result<FloatImage> OutputPass::readLinear() const {
  if (direct_) {
    return makeError("the rasterizer drew this frame without its HDR target (direct output), so it has no linear "
                     "image");
  }
  if (!hdr_ || targetWidth_ == 0) return makeError("the rasterizer has drawn no frame yet");
  std::vector<float> rgba(std::size_t(targetWidth_) * std::size_t(targetHeight_) * 4);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glGetTextureImage(hdr_.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(rgba.size() * sizeof(float)), rgba.data());
  return framePixels(rgba, targetWidth_, targetHeight_, render_.supersample);
}

std::string OutputPass::describe() const {
  if (direct_) {
    return "direct(display values from the fragment shaders: exposure, tone map and curve applied there; RGBA8, no"
           " post pass; into the caller's framebuffer when it is single-sample RGBA8 with float depth (its colour image"
           " with the deferred surfaces' depth-stencil and targets), else copied)";
  }
  return "post(msaa " + std::to_string(render_.msaa) + ", supersample " + std::to_string(render_.supersample) + ")";
}

}  // namespace engine
