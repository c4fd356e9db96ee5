#pragma once
// The analytic shapes of a scene file as triangle meshes, GL-free: the rasterizer
// uploads them (render/mesh.h) and the ray tracer traces the boxes' triangles and
// takes the planes' texture axes from the same transforms, so both draw one shape.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "asset/scene_desc.h"

namespace engine {

struct Vertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec2 uv;
};

struct ShapeData {
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> indices;
};

// A square in the y = 0 plane, `size` wide, `cells` x `cells` quads, uv repeating
// `uvRepeat` times across.
ShapeData makePlane(float size, int cells, float uvRepeat);
// An axis-aligned cube of edge `size` centred on the origin, one uv square per face.
ShapeData makeCube(float size);
// A UV sphere: `rings` x `segments` quads.
ShapeData makeSphere(float radius, int rings, int segments);

// A scene file's analytic primitive as the rasterizer draws it: the unit shape
// (sphere of radius 1, cube of edge 1, plane 2 wide) and the transform that places
// it. A plane without an extent reaches the camera's far distance.
ShapeData shapeForPrimitive(const PrimitiveDesc& primitive);
double planeExtent(const PrimitiveDesc& plane, double farPlane);
glm::dmat4 primitiveTransform(const PrimitiveDesc& primitive, double farPlane);
// Whether primitive `index` of the scene is a plane shape whose material lets no
// light through: it hides what lies behind it (render/plane_occlusion.h) and bounds
// the tracers' terrain split (raytrace/ground_split.h).
bool isOpaquePlane(const SceneDesc& scene, std::size_t index);
// The corners of the unit plane (2 wide) placed by `world`, in order around it.
std::array<glm::dvec3, 4> planeCorners(const glm::dmat4& world);

// The rotation taking unit vector `from` to unit vector `to` (a half turn about x
// when they are opposite): a plane's placement, and so its texture axes.
glm::dmat4 rotationFromTo(const glm::dvec3& from, const glm::dvec3& to);

}  // namespace engine
