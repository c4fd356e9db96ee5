#pragma once
// Reflection probes, the rasterizer's stand-in for the ray tracer's reflected
// rays: a cube map of the scene seen from each mirror shape's centre, which the
// mirror's own draws then sample (SceneDraws). Not part of the engine's interface.
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "asset/scene_desc.h"
#include "core/result.h"
#include "gl/resources.h"
#include "render/scene_view.h"
#include "scene/materials.h"

namespace engine {

class FrameUniforms;
class GpuScene;
class SunShadowPass;
class WorldPass;

class ReflectionProbePass {
 public:
  // One probe of `size` texels a face per mirror sphere or box (its material in the
  // scene's table, `materials`, has reflection > 0), up to four; null where there is none. Planes get none: a
  // plane mirror needs a planar reflection, which this renderer lacks.
  static Result<std::unique_ptr<ReflectionProbePass>> create(const SceneDesc& scene,
                                                             std::span<const SceneMaterial> materials, int size);

  // The mirror shape of each probe, in order (GpuScene's ShapeDraw::probe).
  std::vector<int> shapes() const;
  const gl::Texture& cube(int probe) const { return probes_[size_t(probe)].cube; }

  // Each probe's six faces, seen from the mirror's centre without the mirror
  // itself, drawn by `world`: `gpu`'s characters are placed around it, then back
  // at `cameraPosition`; the sun's maps (`sun`, where the scene has them) are
  // drawn again around it, and the frame block filled for each face.
  Status render(const glm::dvec3& cameraPosition, GpuScene& gpu, SunShadowPass* sun, FrameUniforms& frame,
                WorldPass& world);
  // Probes depend on the scene, not on the camera: a scene where nothing moves
  // draws them once.
  bool drawn() const { return drawn_; }
  // "reflection-probes(1 x cube 256)".
  std::string describe() const;

 private:
  struct Probe {
    int shape = -1;
    glm::dvec3 center{0.0};
    gl::Texture cube;
  };

  std::vector<Probe> probes_;
  int size_ = 0;
  double farPlane_ = 0.0;     // the camera's
  glm::vec3 background_{0.0f};  // the sky's, where it draws nothing
  gl::Renderbuffer depth_;
  gl::Framebuffer fbo_;
  bool drawn_ = false;
};

}  // namespace engine
