// SceneRenderer's shadow passes: the sun's near and far maps, fitted to slices of
// the view, and the point light's cube map.
#include <algorithm>
#include <limits>

#include "render/scene_renderer_impl.h"

namespace engine {

// The bounding sphere of the view frustum's slice [nearPlane, farPlane],
// camera-relative, its radius rounded up to whole metres: a stable size, so that
// texels do not change every frame.
SceneRenderer::Impl::ShadowSphere SceneRenderer::Impl::frustumSlice(const glm::dmat4& view, double fovy, double aspect,
                                                                    double nearPlane, double farPlane) {
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

// The sun's orthographic box around `around` (relative to `eye`), texel-snapped.
SceneRenderer::Impl::SunBox SceneRenderer::Impl::fitSunBox(const ShadowSphere& around) const {
  const double radius = around.radius;
  glm::dvec3 center = around.center;
  const glm::dvec3 l = scene.lights[size_t(sunLight)].direction;
  const glm::dvec3 up = std::abs(l.y) > 0.99 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 lx = glm::normalize(glm::cross(up, l)), ly = glm::cross(l, lx);
  // Snap the centre to whole texels in world space: the map then slides in texel
  // steps as the camera moves, and shadow edges do not shimmer.
  SunBox box;
  box.radius = radius;
  box.texelWorld = 2.0 * radius / double(sunShadowSize);
  const double texel = box.texelWorld;
  const glm::dvec3 world = center + gpu->eye();
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

// The terrain into the sun's shadow map, with the same patches and morph as the
// view (a coarser mesh would poke through the drawn one and shadow it), culled
// against the light's box stretched toward the sun over the whole field: with depth
// clamping, a mountain in front of the light's near plane still casts, at depth 0.
void SceneRenderer::Impl::drawTerrainShadow(const SunBox& box, double fovy, int viewportHeight) {
  const terrain::HeightRange h = terrain->heightRange();
  const double reach = std::hypot(double(terrain->cellsX()), double(terrain->cellsZ())) * terrain->spacing() +
                       double(h.max - h.min);
  const double r = box.radius;
  const glm::dmat4 cullProjection = glm::orthoRH_ZO(-r, r, -r, r, -reach, 2.0 * r + reach);
  const auto selection = selectTerrain(glm::mat4(cullProjection * box.view), fovy, viewportHeight);
  applyPassState(kTerrainShadowPass);
  terrainRenderer->drawDepth(selection, glm::mat4(box.projection * box.view));
  stats->drawCalls += 1;
}

namespace {

// `rect`'s texels (x0 y0 x1 y1, end exclusive) of one map into the other.
void copySunMapRect(const gl::Texture& from, const gl::Texture& to, const glm::ivec4& rect) {
  if (rect.z <= rect.x || rect.w <= rect.y) return;
  glCopyImageSubData(from.id(), GL_TEXTURE_2D, 0, rect.x, rect.y, 0, to.id(), GL_TEXTURE_2D, 0, rect.x, rect.y, 0,
                     rect.z - rect.x, rect.w - rect.y, 1);
}

}  // namespace

// The texels of the near map (sunShadowSize square, through `lightViewProjection`,
// an orthographic box) that `movers` can cover: each character's bounding sphere
// (of every pose: the one view culling trusts) as a cube, its eight corners
// projected, two texels of margin for the rasterizer's rounding at the edges.
glm::ivec4 SceneRenderer::Impl::moversFootprint(const std::vector<DrawItem>& movers,
                                                const glm::mat4& lightViewProjection) const {
  glm::dvec2 low(std::numeric_limits<double>::max()), high(std::numeric_limits<double>::lowest());
  for (const DrawItem& item : movers) {
    const auto [center, r] = gpu->placedSphere(gpu->characters()[size_t(item.object)]);
    for (int corner = 0; corner < 8; ++corner) {
      const glm::dvec3 offset((corner & 1) ? r : -r, (corner & 2) ? r : -r, (corner & 4) ? r : -r);
      const glm::dvec4 clip = glm::dmat4(lightViewProjection) * glm::dvec4(center + offset, 1.0);
      const glm::dvec2 texel = (glm::dvec2(clip) / clip.w * 0.5 + 0.5) * double(sunShadowSize);
      low = glm::min(low, texel);
      high = glm::max(high, texel);
    }
  }
  if (movers.empty()) return glm::ivec4(0);
  const auto clamped = [this](double v) { return int(std::clamp(v, 0.0, double(sunShadowSize))); };
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
Status SceneRenderer::Impl::drawSunNear(const SunBox& box, bool still, double fovy, int viewportHeight) {
  auto casters = collectDraws(nullptr, true);
  if (!casters) return casters.error();
  std::vector<DrawItem> statics, movers;
  for (const DrawItem& item : casters->opaque)
    (item.source == DrawItem::Source::Character ? movers : statics).push_back(item);
  const glm::mat4 lightViewProjection(box.projection * box.view);
  const PassInputs pass{true, lightViewProjection, lightViewProjection};
  sunShadowFbo.bind();
  glViewport(0, 0, sunShadowSize, sunShadowSize);
  applyPassState(kShadowPass);
  glClearDepth(1.0);
  const bool anyStatic = !statics.empty() || terrain;
  if (still && movers.empty() && !sunMapHasMovers) {
    stats->sunStaticKept = 1;
    return Ok{};  // the map is as it was drawn
  }
  if (still && sunStaticValid) {
    stats->sunStaticKept = 1;
    copySunMapRect(sunStaticMap, sunShadowMap, sunMoversRect);
  } else {
    glClear(GL_DEPTH_BUFFER_BIT);
    if (auto s = drawItems(statics, pass); !s) return s;
    if (terrain) drawTerrainShadow(box, fovy, viewportHeight);
    if (still && anyStatic && !movers.empty()) {
      if (sunStaticMap.id() == 0) sunStaticMap = makeSunShadowMap(sunShadowSize);
      copySunMapRect(sunShadowMap, sunStaticMap, glm::ivec4(0, 0, sunShadowSize, sunShadowSize));
      sunStaticValid = true;
    }
  }
  sunMapHasMovers = !movers.empty();
  sunMoversRect = moversFootprint(movers, lightViewProjection);
  return drawItems(movers, pass);
}

// The sun's maps around two spheres relative to `eye` (characters posed for it):
// the near one of everything, the far one of the terrain alone. The frame block's
// shadow matrices then belong to this eye. Either map's static part is drawn again
// only when the camera has moved (see SunMapsKey).
Status SceneRenderer::Impl::renderSunShadow(const ShadowSphere& nearSphere, const ShadowSphere& farSphere,
                                            double fovy, int viewportHeight) {
  const SunBox box = fitSunBox(nearSphere);
  sunTexelWorld = box.texelWorld;
  frame.sunShadowMatrix = box.shadowMatrix;
  SunMapsKey key{gpu->eye(), glm::mat4(box.projection * box.view), glm::mat4(0.0f), fovy, viewportHeight};
  SunBox far;
  if (sunFarShadows) {
    far = fitSunBox(farSphere);
    frame.sunShadowMatrixFar = far.shadowMatrix;
    frame.sunFarParams = glm::vec4(1.0f / float(sunShadowSize), float(far.texelWorld), 0.0f, 0.0f);
    key.farBox = glm::mat4(far.projection * far.view);
  }
  const bool still = sunMapsKey == key;
  if (!still) sunStaticValid = false;
  sunMapsKey = key;
  if (auto s = drawSunNear(box, still, fovy, viewportHeight); !s) return s;
  if (sunFarShadows && !still) {
    // The far map: the terrain alone (mountains over valleys), out to a few km.
    sunShadowFarFbo.bind();
    glClear(GL_DEPTH_BUFFER_BIT);
    drawTerrainShadow(far, fovy, viewportHeight);
  }
  return Ok{};
}

Status SceneRenderer::Impl::renderPointShadow(const glm::dvec3& cameraPosition) {
  const glm::dvec3 light = scene.lights[size_t(pointLights[0])].position - cameraPosition;
  const glm::dmat4 proj = glm::perspectiveRH_ZO(glm::half_pi<double>(), 1.0, pointNear, pointFar);
  glViewport(0, 0, cubeSize, cubeSize);
  applyPassState(kCubeShadowPass);
  glClearDepth(1.0);
  // One list for the six faces: nothing is culled to a face.
  auto casters = collectDraws(nullptr, true);
  if (!casters) return casters.error();
  for (int face = 0; face < 6; ++face) {
    glNamedFramebufferTextureLayer(pointShadowFbo.id(), GL_DEPTH_ATTACHMENT, pointShadowMap.id(), 0, face);
    pointShadowFbo.bind();
    glClear(GL_DEPTH_BUFFER_BIT);
    const glm::mat4 faceViewProjection(proj * glm::lookAt(light, light + kCubeFaceDirections[face], kCubeFaceUps[face]));
    if (auto s = drawItems(casters->opaque, {true, faceViewProjection, faceViewProjection}); !s) return s;
  }
  return Ok{};
}

}  // namespace engine
