#pragma once
// The sun's shadow maps (common/shadows.glsl): the near map of every caster over
// the first kSunShadowDistance metres of the view, and in terrain scenes the far
// map of the terrain alone out to kSunFarShadowDistance; each an orthographic box
// fitted to a slice of the view, texel-snapped. While the camera stands still,
// what does not move is not drawn again (MapsKey). Not part of the engine's
// interface.
#include <memory>
#include <string>
#include <optional>
#include <vector>

#include "asset/scene_desc.h"
#include "core/result.h"
#include "gl/resources.h"
#include "gl/shader.h"
#include "render/draw_items.h"
#include "render/frame_block.h"

namespace engine {

class GpuScene;
class SceneDraws;
class TerrainPass;
struct SceneStats;

inline constexpr double kSunShadowDistance = 60.0;  // metres of view the sun's map covers
inline constexpr double kSunFarShadowDistance = 4000.0;  // and the far (terrain) map

// What a sun map must cover: a sphere, relative to the GPU scene's eye.
struct ShadowSphere {
  glm::dvec3 center{0.0};
  double radius = 0.0;
};

// The bounding sphere of the view frustum's slice [nearPlane, farPlane],
// camera-relative, its radius rounded up to whole metres: a stable size, so that
// texels do not change every frame.
ShadowSphere frustumSlice(const glm::dmat4& view, double fovy, double aspect, double nearPlane, double farPlane);

class SunShadowPass {
 public:
  // Maps of `size` texels square for `sun`; the far one where `farMap` (its
  // terrain is `terrain`'s). Draws what `draws` collects of `gpu`.
  static Result<std::unique_ptr<SunShadowPass>> create(const LightDesc& sun, int size, bool farMap, GpuScene& gpu,
                                                       SceneDraws& draws, TerrainPass* terrain, SceneStats* stats);
  // Turns the light toward `direction` (toward the sun) for the next maps.
  void setDirection(const glm::dvec3& direction) { direction_ = glm::normalize(direction); }

  // The maps around two spheres relative to the GPU scene's eye (characters
  // placed for it): the near one of everything, the far one of the terrain alone.
  // The frame block's shadow matrices (fill) then belong to this eye. Either map's
  // static part is drawn again only when the camera has moved.
  Status render(const ShadowSphere& nearSphere, const ShadowSphere& farSphere, double fovy, int viewportHeight);
  // A scene program's sun shadow uniforms and maps.
  void setUniforms(const gl::Program& program) const;
  // Whether a colour pass's draw may leave the far map out (ShaderVariant::
  // nearSunOnly): the near map covers its bounds, relative to the eye, fully.
  bool nearCovers(const glm::dvec3& lo, const glm::dvec3& hi) const;
  void fill(FrameBlock& frame) const;
  int size() const { return size_; }
  // "shadow-sun(2048, pcf 3)", and " shadow-sun-far(2048, terrain, 4000 m)" with
  // the far map; `filter`: the shadows' ("pcf 3", "hard").
  std::string describe(const std::string& filter) const;
  bool hasFarMap() const { return far_; }

 private:
  struct SunBox {
    glm::dmat4 view{1.0}, projection{1.0};  // camera-relative world -> the light's clip space
    glm::mat4 shadowMatrix{1.0f};           // camera-relative world -> map [0,1]^3
    double radius = 0.0, texelWorld = 0.0;
  };
  // What the maps were last drawn for: while it holds (a still camera), what does
  // not move (shapes, the terrain) is not drawn again. The near map's static
  // casters alone are kept in `staticMap_` (made the second still frame, so that a
  // moving camera pays nothing) and copied back under the characters each frame.
  struct MapsKey {
    glm::dvec3 eye{0.0};
    glm::mat4 nearBox{0.0f}, farBox{0.0f};
    double fovy = 0.0;
    int viewportHeight = 0;
    bool operator==(const MapsKey&) const = default;
  };

  SunShadowPass(GpuScene& gpu, SceneDraws& draws, TerrainPass* terrain, SceneStats* stats)
      : gpu_(gpu), draws_(draws), terrain_(terrain), stats_(stats) {}
  SunBox fitBox(const ShadowSphere& sphere) const;
  void drawTerrain(const SunBox& box, double fovy, int viewportHeight);
  Status drawNear(const SunBox& box, bool still, double fovy, int viewportHeight);
  glm::ivec4 moversFootprint(const std::vector<DrawItem>& movers, const glm::mat4& lightViewProjection) const;

  GpuScene& gpu_;
  SceneDraws& draws_;
  TerrainPass* terrain_;
  SceneStats* stats_;
  glm::dvec3 direction_{0.0};  // toward the sun
  int size_ = 0;
  bool far_ = false;
  gl::Texture map_, farMap_;
  gl::Framebuffer fbo_, farFbo_;
  // The last render's: texel size in metres and matrices (fill).
  double texelWorld_ = 0.0;
  glm::mat4 shadowMatrix_{1.0f}, farShadowMatrix_{1.0f};
  glm::vec4 farParams_{0.0f};
  std::optional<MapsKey> key_;
  gl::Texture staticMap_;
  bool staticValid_ = false;   // staticMap_ holds the static casters for key_
  bool mapHasMovers_ = false;  // map_ holds characters too
  // The near map's texels the characters may have written in it last, x0 y0 x1 y1
  // (end exclusive): all a kept map's static depth needs back.
  glm::ivec4 moversRect_{0};
};

}  // namespace engine
