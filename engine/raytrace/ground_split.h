#pragma once
// The terrain split at the scene's ground, for the tracers' BVH. GL-free.
//
// A BVH's boxes are drawn around triangles, not around the rays that meet them. On
// demo.json the valley floor lies under the plaza (an opaque plane at y = 0) and the
// hills rise around it, so every box near the top of the terrain's tree reaches from
// below the plaza to above it: the camera's rays that land on the plaza, the shadow
// rays that leave it and the sky's rays all entered four to six of those nodes before
// the boxes grew small enough to miss (8.3 M nodes a 1280x720 frame). The triangles
// wholly behind the plane, seen from the camera, go to a BVH group of their own whose
// root box lies behind it: those rays reject it with one box test, and the rest of the
// terrain gets boxes around the hills alone (4.1 M nodes, the same image bytes).
//
// No triangle is dropped or changed, only grouped: a ray that does reach behind the
// plane (past its edge, or through it when the camera moves) meets the same triangles,
// so where the split is not worth it it costs speed, never correctness.
#include <optional>

#include <glm/glm.hpp>

#include "asset/scene_desc.h"
#include "raytrace/rt_scene.h"

namespace engine::rt {

// A plane as signedDistance(p) = dot(normal, p) + offset, positive on the camera's side.
struct GroundPlane {
  glm::dvec3 normal{0.0, 1.0, 0.0};
  double offset = 0.0;
  double signedDistance(const glm::dvec3& p) const { return glm::dot(normal, p) + offset; }
};

// The scene's largest plane shape that lets no light through, facing the camera;
// nothing when there is none or the camera lies in its plane.
std::optional<GroundPlane> groundPlane(const SceneDesc& scene);

// Moves the triangles of `mesh` that lie wholly behind `ground` (each corner strictly
// on its far side) into the mesh returned, with the vertices they use; `mesh` keeps
// the others and its vertices that they use. Both keep their triangles' order and
// corners, so a hit on either is the hit on the mesh before, bit for bit.
RtMesh takeTrianglesBehind(RtMesh& mesh, const GroundPlane& ground);

}  // namespace engine::rt
