#include "render/sun_shadow_pass.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <sstream>

#include "gl/bindings.h"
#include "render/gpu_scene.h"
#include "render/pass_state.h"
#include "render/scene_draws.h"
#include "render/scene_stats.h"
#include "render/sun_coverage.h"
#include "render/terrain_pass.h"

namespace engine {
namespace {

// A depth map compared in hardware (sampler2DShadow): the two maps and the near
// map's copy of its static casters, one format, as glCopyImageSubData needs.
gl::Texture makeSunShadowMap(int size) {
  gl::Texture map = gl::Texture::create2D(GL_DEPTH_COMPONENT32F, size, size, 1);
  map.parameter(GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  map.parameter(GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  map.parameter(GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  map.parameter(GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  map.parameter(GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  map.parameter(GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return map;
}

// `rect`'s texels (x0 y0 x1 y1, end exclusive) of one map into the other.
void copySunMapRect(const gl::Texture& from, const gl::Texture& to, const glm::ivec4& rect) {
  if (rect.z <= rect.x || rect.w <= rect.y) return;
  glCopyImageSubData(from.id(), GL_TEXTURE_2D, 0, rect.x, rect.y, 0, to.id(), GL_TEXTURE_2D, 0, rect.x, rect.y, 0,
                     rect.z - rect.x, rect.w - rect.y, 1);
}

}  // namespace

ShadowSphere frustumSlice(const glm::dmat4& view, double fovy, double aspect, double nearPlane, double farPlane) {
  const glm::dmat4 invView = glm::inverse(view);
  const double ty = std::tan(fovy * 0.5), tx = ty * aspect;
  glm::dvec3 corners[8];
  int k = 0;
  for (double d : {nearPlane, farPlane})
    for (double sy : {-1.0, 1.0})
      for (double sx : {-1.0, 1.0}) corners[k++] = glm::dvec3(invView * glm::dvec4(sx * tx * d, sy * ty * d, -d, 1.0));
  ShadowSphere slice;
  for (const auto& c : corners) slice.center += c / 8.0;
  for (const auto& c : corners) slice.radius = std::max(slice.radius, glm::length(c - slice.center));
  slice.radius = std::ceil(slice.radius);
  return slice;
}

Result<std::unique_ptr<SunShadowPass>> SunShadowPass::create(const LightDesc& sun, int size, bool farMap,
                                                             GpuScene& gpu, SceneDraws& draws, TerrainPass* terrain,
                                                             SceneStats* stats) {
  std::unique_ptr<SunShadowPass> pass(new SunShadowPass(gpu, draws, terrain, stats));
  pass->direction_ = sun.direction;
  pass->size_ = size;
  pass->far_ = farMap;
  pass->map_ = makeSunShadowMap(size);
  pass->fbo_ = gl::Framebuffer::create();
  pass->fbo_.attach(GL_DEPTH_ATTACHMENT, pass->map_);
  if (auto s = pass->fbo_.check("shadow-sun"); !s) return s.error();
  if (farMap) {
    pass->farMap_ = makeSunShadowMap(size);
    pass->farFbo_ = gl::Framebuffer::create();
    pass->farFbo_.attach(GL_DEPTH_ATTACHMENT, pass->farMap_);
    if (auto s = pass->farFbo_.check("shadow-sun-far"); !s) return s.error();
  }
  return pass;
}

// The sun's orthographic box around `around` (relative to the eye), texel-snapped.
SunShadowPass::SunBox SunShadowPass::fitBox(const ShadowSphere& around) const {
  const double radius = around.radius;
  glm::dvec3 center = around.center;
  const glm::dvec3 l = direction_;
  const glm::dvec3 up = std::abs(l.y) > 0.99 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 lx = glm::normalize(glm::cross(up, l)), ly = glm::cross(l, lx);
  // Snap the centre to whole texels in world space: the map then slides in texel
  // steps as the camera moves, and shadow edges do not shimmer.
  SunBox box;
  box.radius = radius;
  box.texelWorld = 2.0 * radius / double(size_);
  const double texel = box.texelWorld;
  const glm::dvec3 world = center + gpu_.eye();
  const double u = glm::dot(world, lx), v = glm::dot(world, ly);
  center += lx * (std::floor(u / texel) * texel - u) + ly * (std::floor(v / texel) * texel - v);

  const double casterMargin = 200.0;  // casters behind the view still throw shadows into it
  box.view = glm::lookAt(center + l * (radius + casterMargin), center, ly);
  box.projection = glm::orthoRH_ZO(-radius, radius, -radius, radius, 0.0, 2.0 * radius + casterMargin);
  const glm::dmat4 bias = glm::translate(glm::dmat4(1.0), glm::dvec3(0.5, 0.5, 0.0)) *
                          glm::scale(glm::dmat4(1.0), glm::dvec3(0.5, 0.5, 1.0));
  box.shadowMatrix = glm::mat4(bias * box.projection * box.view);
  return box;
}

// The terrain into a sun map, with the same patches and morph as the view (a
// coarser mesh would poke through the drawn one and shadow it), culled against the
// light's box stretched toward the sun over the whole field: with depth clamping, a
// mountain in front of the light's near plane still casts, at depth 0.
void SunShadowPass::drawTerrain(const SunBox& box, double fovy, int viewportHeight) {
  const terrain::Terrain& terrain = terrain_->terrain();
  const terrain::HeightRange h = terrain.heightRange();
  const double reach = std::hypot(double(terrain.cellsX()), double(terrain.cellsZ())) * terrain.spacing() +
                       double(h.max - h.min);
  const double r = box.radius;
  const glm::dmat4 cullProjection = glm::orthoRH_ZO(-r, r, -r, r, -reach, 2.0 * r + reach);
  const auto selection = terrain_->select(glm::mat4(cullProjection * box.view), fovy, viewportHeight);
  applyPassState(kTerrainShadowPass);
  terrain_->renderer().drawDepth(selection, glm::mat4(box.projection * box.view));
  stats_->drawCalls += 1;
}

// The texels of the near map (through `lightViewProjection`, an orthographic box)
// that `movers` can cover: each character's bounding sphere (of every pose: the one
// view culling trusts) as a cube, its eight corners projected, two texels of margin
// for the rasterizer's rounding at the edges.
glm::ivec4 SunShadowPass::moversFootprint(const std::vector<DrawItem>& movers,
                                          const glm::mat4& lightViewProjection) const {
  glm::dvec2 low(std::numeric_limits<double>::max()), high(std::numeric_limits<double>::lowest());
  for (const DrawItem& item : movers) {
    const auto [center, r] = gpu_.placedSphere(gpu_.characters()[size_t(item.object)]);
    for (int corner = 0; corner < 8; ++corner) {
      const glm::dvec3 offset((corner & 1) ? r : -r, (corner & 2) ? r : -r, (corner & 4) ? r : -r);
      const glm::dvec4 clip = glm::dmat4(lightViewProjection) * glm::dvec4(center + offset, 1.0);
      const glm::dvec2 texel = (glm::dvec2(clip) / clip.w * 0.5 + 0.5) * double(size_);
      low = glm::min(low, texel);
      high = glm::max(high, texel);
    }
  }
  if (movers.empty()) return glm::ivec4(0);
  const auto clamped = [this](double v) { return int(std::clamp(v, 0.0, double(size_))); };
  return {clamped(std::floor(low.x) - 2.0), clamped(std::floor(low.y) - 2.0), clamped(std::ceil(high.x) + 2.0),
          clamped(std::ceil(high.y) + 2.0)};
}

// The near map: every caster (the sun's box is fitted to what the view sees, not
// culled to it). A depth-only pass keeps the nearest depth whatever the order of
// the draws, so the shapes and the terrain may go first and the characters over
// them: while the camera stands still, the static casters' depth is copied back
// from the frame that drew them where the characters were drawn last (the rest of
// the map still holds it: on llvmpipe the whole 16 MB copy took about 2 ms on the
// thread that submits), and only the characters are drawn again.
Status SunShadowPass::drawNear(const SunBox& box, bool still, double fovy, int viewportHeight) {
  auto casters = draws_.collect(nullptr, true);
  if (!casters) return casters.error();
  std::vector<DrawItem> statics, movers;
  for (const DrawItem& item : casters->opaque)
    (item.source == DrawItem::Source::Character ? movers : statics).push_back(item);
  const glm::mat4 lightViewProjection(box.projection * box.view);
  const PassInputs pass{true, lightViewProjection, lightViewProjection};
  fbo_.bind();
  glViewport(0, 0, size_, size_);
  applyPassState(kShadowPass);
  glClearDepth(1.0);
  const bool anyStatic = !statics.empty() || terrain_;
  if (still && movers.empty() && !mapHasMovers_) {
    stats_->sunStaticKept = 1;
    return Ok{};  // the map is as it was drawn
  }
  if (still && staticValid_) {
    stats_->sunStaticKept = 1;
    copySunMapRect(staticMap_, map_, moversRect_);
  } else {
    glClear(GL_DEPTH_BUFFER_BIT);
    if (auto s = draws_.draw(statics, pass); !s) return s;
    if (terrain_) drawTerrain(box, fovy, viewportHeight);
    if (still && anyStatic && !movers.empty()) {
      if (staticMap_.id() == 0) staticMap_ = makeSunShadowMap(size_);
      copySunMapRect(map_, staticMap_, glm::ivec4(0, 0, size_, size_));
      staticValid_ = true;
    }
  }
  mapHasMovers_ = !movers.empty();
  moversRect_ = moversFootprint(movers, lightViewProjection);
  return draws_.draw(movers, pass);
}

Status SunShadowPass::render(const ShadowSphere& nearSphere, const ShadowSphere& farSphere, double fovy,
                             int viewportHeight) {
  const SunBox box = fitBox(nearSphere);
  texelWorld_ = box.texelWorld;
  shadowMatrix_ = box.shadowMatrix;
  MapsKey key{gpu_.eye(), glm::mat4(box.projection * box.view), glm::mat4(0.0f), fovy, viewportHeight};
  SunBox far;
  if (far_) {
    far = fitBox(farSphere);
    farShadowMatrix_ = far.shadowMatrix;
    farParams_ = glm::vec4(1.0f / float(size_), float(far.texelWorld), 0.0f, 0.0f);
    key.farBox = glm::mat4(far.projection * far.view);
  }
  const bool still = key_ == key;
  if (!still) staticValid_ = false;
  key_ = key;
  if (auto s = drawNear(box, still, fovy, viewportHeight); !s) return s;
  if (far_ && !still) {
    // The far map: the terrain alone (mountains over valleys), out to a few km.
    farFbo_.bind();
    glClear(GL_DEPTH_BUFFER_BIT);
    drawTerrain(far, fovy, viewportHeight);
  }
  return Ok{};
}

void SunShadowPass::setUniforms(const gl::Program& program) const {
  program.set("u_sunTexelWorld", float(texelWorld_));
  map_.bind(gl::binding::kSunShadow);
  if (far_) farMap_.bind(gl::binding::kSunShadowFar);
}

// The far map's nine taps run for every fragment of a program that has them
// (llvmpipe runs both sides of an `if`): about 15 CPU ms of demo.json's frame,
// whose shapes and robots all lie where the near map covers.
bool SunShadowPass::nearCovers(const glm::dvec3& lo, const glm::dvec3& hi) const {
  return far_ && withinNearSunMap(glm::dmat4(shadowMatrix_), lo, hi, texelWorld_);
}

void SunShadowPass::fill(FrameBlock& frame) const {
  frame.u_sunShadowMatrix = shadowMatrix_;
  if (!far_) return;
  frame.u_sunShadowMatrixFar = farShadowMatrix_;
  frame.u_sunFarParams = farParams_;
}

std::string SunShadowPass::describe(const std::string& filter) const {
  std::ostringstream out;
  out << "shadow-sun(" << size_ << ", " << filter << ")";
  if (far_) out << " shadow-sun-far(" << size_ << ", terrain, " << kSunFarShadowDistance << " m)";
  return out.str();
}

}  // namespace engine
