#pragma once
// The pixels a camera-relative sphere can cover in a view, for scissoring a pass
// to what it can touch (the deferred characters' shading). GL-free.
#include <glm/glm.hpp>

namespace engine {

// Pixels [x0, x1) x [y0, y1) of a width x height view, GL's window coordinates
// (y up), that hold every point of the sphere that `viewProjection` puts in front of
// the eye: its bounding box's eight corners projected, widened by a pixel each way,
// clamped to the view. The whole view when a corner lies at or behind the eye's
// plane (the projection's w <= 0), where the box has no bounded image.
glm::ivec4 sphereScreenRect(const glm::dmat4& viewProjection, const glm::dvec3& center, double radius, int width,
                            int height);

}  // namespace engine
