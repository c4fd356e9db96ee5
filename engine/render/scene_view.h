#pragma once
// What the scene renderer's passes share (render/scene_renderer.h): where a pass
// looks from, the draw lists of one view and how a pass draws them. Not part of the
// engine's interface.
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "render/draw_items.h"
#include "render/model_renderer.h"

namespace engine {

// GL's cube face order, and the view axes that put each face's image where the
// cube map's lookup expects it.
inline constexpr glm::dvec3 kCubeFaceDirections[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
inline constexpr glm::dvec3 kCubeFaceUps[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};

// Where a scene pass looks from: the camera, or one face of a reflection probe.
struct View {
  glm::dmat4 viewProjection{1.0};
  glm::dvec4 planes[6];
  double fovy = 1.0;
  int width = 1, height = 1;
  bool mirrored = false;  // a left-handed camera: faces wind the other way
  // The camera's own view: only it copies its opaque pass for transmissive surfaces
  // to refract (probe views refract the camera's last copy).
  bool main = false;
};

// What the draws of one pass share besides the items themselves.
struct PassInputs {
  bool depthOnly = false;
  glm::mat4 lightViewProjection{1.0f};  // shadow passes
  glm::mat4 viewProjection{1.0f};
  bool useProbes = false;  // mirrors show their reflection probe
  bool surface = false;    // the deferred characters' surface pass (CharacterSurfaces::draw)
};

// GPU culling's commands for each item of a draw list, aligned with it: one per
// instance drawn (a shape's one, a glTF node's mesh instances); empty for a plain
// draw (culling off, or a primitive without clusters).
using ItemCommands = std::vector<std::vector<IndirectDraw>>;

// The opaque and the blended draws of one view; the opaque ones of transmissive
// materials (KHR_materials_transmission) apart, as they refract the others.
struct DrawLists {
  std::vector<DrawItem> opaque, transmissive, blend;
  // Opaque character primitives shaded once a pixel (CharacterSurfaces), apart.
  std::vector<DrawItem> surface;
  bool refracts = false;  // some item, opaque or blended, is transmissive
};

// The stencil of a frame with deferred surfaces: 1 marks the deferred terrain's
// pixels (TerrainPass::beginSurface), each surface group of the characters its own
// value from 2 up (CharacterSurfaces::draw).
inline constexpr int kTerrainStencil = 1;
inline constexpr int kFirstSurfaceStencil = 2;
inline constexpr std::size_t kMaxSurfaceGroups = 256 - kFirstSurfaceStencil;

// Reverse-Z projection (near maps to 1, far to 0) for GL_ZERO_TO_ONE clip space:
// float depth then spends its precision evenly across distance.
inline glm::dmat4 reverseZProjection(double fovyRadians, double aspect, double nearPlane, double farPlane) {
  return glm::perspectiveRH_ZO(fovyRadians, aspect, farPlane, nearPlane);
}

// The six planes of a view-projection (Gribb-Hartmann), normalised, inside >= 0.
inline void frustumPlanes(const glm::dmat4& m, glm::dvec4 planes[6]) {
  const glm::dvec4 row0(m[0][0], m[1][0], m[2][0], m[3][0]);
  const glm::dvec4 row1(m[0][1], m[1][1], m[2][1], m[3][1]);
  const glm::dvec4 row2(m[0][2], m[1][2], m[2][2], m[3][2]);
  const glm::dvec4 row3(m[0][3], m[1][3], m[2][3], m[3][3]);
  planes[0] = row3 + row0;
  planes[1] = row3 - row0;
  planes[2] = row3 + row1;
  planes[3] = row3 - row1;
  planes[4] = row2;         // zero-to-one depth: z >= 0
  planes[5] = row3 - row2;  // z <= w
  for (int i = 0; i < 6; ++i) planes[i] /= glm::length(glm::dvec3(planes[i]));
}

}  // namespace engine
