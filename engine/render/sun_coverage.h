#pragma once
// Where the sun's near map covers a draw fully, on the CPU. GL-free.
//
// common/shadows.glsl weighs the near map by `inside`: 1 where the lookup point
// (the surface point moved along its normal by 1.5 shadow texels) lies in the map's
// depth range and at least a tenth of the map from every edge, fading to 0 beyond.
// The far map's lookups are then weighed by 1 - inside = 0, so a draw whose every
// lookup point has inside == 1 can leave them out (ShaderVariant::nearSunOnly) and
// give the same bytes: mix(far, near, 1.0) is near exactly.
#include <glm/glm.hpp>

namespace engine {

// The inner part's edge, as a fraction of the map (shadows.glsl's smoothstep).
inline constexpr double kSunMapFadeWidth = 0.1;
// Kept clear of that edge and of the depth range's ends, in map units, for the
// float rounding of the shader's own transform (about 1e-7 of the map).
inline constexpr double kSunCoverageMargin = 1e-4;

// Whether every point of the box lo..hi (camera-relative, as the shaders' positions)
// looks the near map up where it covers fully: `shadowMatrix` maps those positions
// to the map's uv and depth (an orthographic box: w stays 1), `texelWorld` is a
// shadow texel's world size (the normal offset's unit).
bool withinNearSunMap(const glm::dmat4& shadowMatrix, const glm::dvec3& lo, const glm::dvec3& hi, double texelWorld);

}  // namespace engine
