#pragma once
// Occlusion by a scene's opaque planes, on the CPU. GL-free.
//
// A plane shape is a flat quad drawn opaque in every view that sees it. A box lying
// wholly on the far side of its plane from the eye, whose outline on screen lies
// wholly inside the quad's, is hidden at every pixel it covers: along each pixel's
// ray the quad comes first. On demo.json the plaza's ground hides the valley floor
// beneath it, and there the terrain's CDLOD selection puts its finest patches (the
// ones nearest the camera): left undrawn, they cost no rasterizing, and the image
// is the same bytes, since every fragment they had failed the depth test.
//
// Margins keep that true with the rounding of real rasterizing: the box's outline
// stays kPlanePixelMargin pixels inside the quad's (llvmpipe snaps vertices to 1/256 of a
// pixel), and each corner lies behind the plane by kPlaneDepthMargin of the eye's
// distance from it (the relative gap between the two depths at a pixel, against
// float depth's 6e-8) plus kPlaneRoundingMargin of its own distance (camera-relative
// float positions).
#include <array>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "asset/scene_desc.h"

namespace engine::cull {

inline constexpr double kPlanePixelMargin = 2.0;
inline constexpr double kPlaneDepthMargin = 1e-3;
inline constexpr double kPlaneRoundingMargin = 1e-5;

// The quad as one view draws it: its plane (camera-relative, the eye on the
// positive side: dot(normal, p) + offset) and its outline in pixels, clipped to the
// view's near plane, counter-clockwise.
struct ScreenQuad {
  glm::dvec3 normal{0.0};
  double offset = 0.0;
  std::vector<glm::dvec2> outline;
};

// `corners` camera-relative, in order around the quad; a two-sided quad (every
// plane shape is). Nothing when the eye lies in its plane or it is out of view.
std::optional<ScreenQuad> screenQuad(const std::array<glm::dvec3, 4>& corners, const glm::dmat4& viewProjection,
                                     glm::dvec2 viewport);

// The scene's plane shapes whose material lets nothing through, as a view from
// `eye` with `viewProjection` (camera-relative) sees them; shape `skip` (a
// reflection probe's own mirror, not drawn in its views) left out.
std::vector<ScreenQuad> opaquePlanes(const SceneDesc& scene, const glm::dvec3& eye, const glm::dmat4& viewProjection,
                                     glm::dvec2 viewport, int skip = -1);

// Whether the quad hides the box (camera-relative, lo..hi) from the eye, margins
// included. False whenever a corner lies behind the eye. `pixelMargin` other than
// kPlanePixelMargin: tests only (a negative one hides what shows).
bool hidesBox(const ScreenQuad& quad, const glm::dvec3& lo, const glm::dvec3& hi, const glm::dmat4& viewProjection,
              glm::dvec2 viewport, double pixelMargin = kPlanePixelMargin);

}  // namespace engine::cull
