#pragma once
// Triangle meshes: CPU data, procedural shapes, and their GPU copy.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "asset/scene_desc.h"
#include "gl/resources.h"

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

// Vertex attribute locations shared with shaders/common/vertex.glsl.
inline constexpr GLuint kPositionLocation = 0;
inline constexpr GLuint kNormalLocation = 1;
inline constexpr GLuint kUvLocation = 2;

class GpuMesh {
 public:
  explicit GpuMesh(const ShapeData& data);
  void draw() const;
  GLsizei indexCount() const { return indexCount_; }

 private:
  gl::Buffer vertices_;
  gl::Buffer indices_;
  gl::VertexArray vao_;
  GLsizei indexCount_ = 0;
};

}  // namespace engine
