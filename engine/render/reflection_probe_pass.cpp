#include "render/reflection_probe_pass.h"

#include <algorithm>
#include <string>

#include "render/frame_uniforms.h"
#include "render/gpu_scene.h"
#include "render/pass_state.h"
#include "render/sun_shadow_pass.h"
#include "render/world_pass.h"

namespace engine {
namespace {

constexpr int kMaxReflectionProbes = 4;
constexpr double kProbeNear = 0.01;

}  // namespace

Result<std::unique_ptr<ReflectionProbePass>> ReflectionProbePass::create(const SceneDesc& scene,
                                                                         std::span<const SceneMaterial> materials,
                                                                         int size) {
  if (size <= 0) return std::unique_ptr<ReflectionProbePass>();
  auto pass = std::make_unique<ReflectionProbePass>();
  pass->size_ = size;
  pass->farPlane_ = scene.camera.farPlane;
  pass->background_ = scene.sky.background;
  for (int i = 0; i < int(scene.primitives.size()) && int(pass->probes_.size()) < kMaxReflectionProbes; ++i) {
    const PrimitiveDesc& p = scene.primitives[size_t(i)];
    if (p.type == PrimitiveType::Plane || materials[size_t(p.material)].surface.reflection <= 0.0f) continue;
    Probe probe;
    probe.shape = i;
    probe.center = p.type == PrimitiveType::Sphere ? p.center : (p.min + p.max) * 0.5;
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &id);
    glTextureStorage2D(id, 1, GL_RGBA16F, size, size);
    probe.cube = gl::Texture::adopt(id, size, size);
    probe.cube.parameter(GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    probe.cube.parameter(GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    pass->probes_.push_back(std::move(probe));
  }
  if (pass->probes_.empty()) return std::unique_ptr<ReflectionProbePass>();
  glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);  // no seams where faces meet
  pass->depth_ = gl::Renderbuffer::create(GL_DEPTH_COMPONENT32F, size, size);
  pass->fbo_ = gl::Framebuffer::create();
  pass->fbo_.attach(GL_DEPTH_ATTACHMENT, pass->depth_);
  glNamedFramebufferTextureLayer(pass->fbo_.id(), GL_COLOR_ATTACHMENT0, pass->probes_[0].cube.id(), 0, 0);
  if (auto s = pass->fbo_.check("reflection-probe"); !s) return s.error();
  return pass;
}

std::vector<int> ReflectionProbePass::shapes() const {
  std::vector<int> out;
  for (const Probe& probe : probes_) out.push_back(probe.shape);
  return out;
}

// Positions stay camera-relative, now to the probe's centre. The sun's maps are
// drawn again around the probe: the camera's maps cover what the camera sees, and
// a static scene keeps its probes however far the camera then goes. Probes show no
// mirrors: one bounce, where the ray tracer follows --max-depth bounces. Before the
// camera's own sun maps, which this overwrites.
Status ReflectionProbePass::render(const glm::dvec3& cameraPosition, GpuScene& gpu, SunShadowPass* sun,
                                   FrameUniforms& frame, WorldPass& world) {
  const glm::dmat4 projection = reverseZProjection(glm::half_pi<double>(), 1.0, kProbeNear, farPlane_);
  for (const Probe& probe : probes_) {
    gpu.place(probe.center);
    if (sun) {
      // All around the probe, as far as the camera's maps reach ahead of it.
      const ShadowSphere nearSphere{glm::dvec3(0.0), std::min(farPlane_, kSunShadowDistance)};
      const ShadowSphere farSphere{glm::dvec3(0.0), std::min(farPlane_, kSunFarShadowDistance)};
      if (auto s = sun->render(nearSphere, farSphere, glm::half_pi<double>(), size_); !s) return s;
    }
    glViewport(0, 0, size_, size_);
    for (int face = 0; face < 6; ++face) {
      View view;
      view.viewProjection = projection * glm::lookAt(glm::dvec3(0.0), kCubeFaceDirections[face], kCubeFaceUps[face]);
      frustumPlanes(view.viewProjection, view.planes);
      view.fovy = glm::half_pi<double>();
      view.width = view.height = size_;
      frame.fill(probe.center, glm::mat4(view.viewProjection));
      glNamedFramebufferTextureLayer(fbo_.id(), GL_COLOR_ATTACHMENT0, probe.cube.id(), 0, face);
      fbo_.bind();
      applyPassState(opaquePassFor(false));  // depth writes on, for the clear
      glClearColor(background_.r, background_.g, background_.b, 1.0f);
      glClearDepth(0.0);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      if (auto s = world.draw(view, probe.shape, false); !s) return s;
    }
  }
  gpu.place(cameraPosition);
  drawn_ = true;
  return Ok{};
}

std::string ReflectionProbePass::describe() const {
  return "reflection-probes(" + std::to_string(probes_.size()) + " x cube " + std::to_string(size_) + ")";
}

}  // namespace engine
