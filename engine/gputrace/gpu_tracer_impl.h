#pragma once
// GpuTracer's insides, shared by the files of its kernels (gpu_tracer.cpp: ray queries
// and the Whitted integrator; path_kernel.cpp: the path tracer). Not an interface.
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "gl/resources.h"
#include "gl/shader.h"
#include "gputrace/gpu_tracer.h"
#include "gputrace/gpu_layout.h"

namespace engine::gpurt {
namespace detail {

// A storage buffer of `items`; an empty array gets 16 bytes, as GL wants a size, and
// the shader's count uniform keeps it unread.
template <typename T>
gl::Buffer storage(const std::vector<T>& items) {
  if (items.empty()) return gl::Buffer::create(16);
  return gl::Buffer::create(items.size() * sizeof(T), items.data());
}

// The constants trace.glsl takes from the C++ compiler (see there), and for an
// integrator what its scene `shaded` needs built in (rt/material_at.glsl): RT_TEXTURES
// (some material reads a texture or is the terrain's), RT_TRIANGLE_UVS and
// RT_TRIANGLE_COLORS (the layout's triangle attributes, RT_ATTRIBUTE_SLOTS a
// triangle), RT_PASS_THROUGH (some material is not opaque or is single-sided),
// RT_TRANSPARENT (not opaque: shadow rays pass it), RT_SKY_IMAGE, RT_SHEEN_TABLE.
std::vector<std::string> traceDefines(const rt::GpuSceneLayout& layout, const rt::RtScene* shaded);
// Whether some material of the scene has a sheen (RT_SHEEN_TABLE: the integrators read
// its albedo table).
bool hasSheen(const rt::RtScene& scene);

}  // namespace detail

struct GpuTracer::State {
  const rt::RtScene* scene = nullptr;
  std::string shaderDir;
  rt::GpuSceneLayout layout;
  gl::Buffer nodes, leaves, order, instances, spheres, planes, triangles, materials, lights;
  gl::Buffer triangleAttributes, textures, texels, skyImage;  // placeholders where the scene has none
  gl::Buffer sheenTable;  // the Whitted kernel's (RT_SHEEN_TABLE); the path tracer's follows its environment's tables
  gl::Program hits;
  mutable std::map<int, gl::Program> whitted;  // by maxDepth, built on first use
  mutable std::optional<gl::Program> path;     // built on first use

  // Binds the scene's buffers and makes `program` current, with the counts trace.glsl reads.
  void bindScene(const gl::Program& program) const;
  // What both integrators read alike: the image size, the camera (rt/camera.glsl),
  // the sky (rt/sky.glsl), the fog and the seed.
  void setView(const gl::Program& program, const rt::RenderSettings& settings) const;
  // `batches` dispatches of `program`, one invocation per pixel of rows [firstRow,
  // firstRow + rows) of a `width` wide image in 8 x 8 groups, `prepare(batch)` setting
  // each one's uniforms first; timed from dispatch to glFinish. The band's image is
  // read back after the last (a kernel may add to what the one before wrote), the
  // three ray counters (primary, shadow, reflection or bounce) after each, summed in
  // 64 bits.
  rt::RenderResult runPerPixel(const gl::Program& program, int width, int firstRow, int rows, int batches = 1,
                               const std::function<void(int)>& prepare = {}) const;
};

}  // namespace engine::gpurt
