#pragma once
// Each view's draw items (render/draw_items.h): the GPU scene's shapes and
// character primitives culled to the view, each with its program, sorted; and
// their submission in the pass state the caller set. Every pass draws through it;
// it owns the scene programs' shader variants, all built at load. Not part of the
// engine's interface.
#include <memory>
#include <vector>

#include "asset/scene_desc.h"
#include "core/result.h"
#include "render/model_renderer.h"
#include "render/scene_view.h"

namespace engine {

class CharacterSurfacePass;
class GpuScene;
class PointShadowPass;
class ReflectionProbePass;
class SunShadowPass;
struct SceneStats;
struct ShapeDraw;
struct CharacterDraw;

// The passes whose results the draws of other passes read, where the scene has
// them: the shadow maps every lit program samples, the probes' cubes that mirrors
// show, the deferred characters' groups.
struct DrawSources {
  const SunShadowPass* sun = nullptr;
  const PointShadowPass* point = nullptr;
  const ReflectionProbePass* probes = nullptr;
  const CharacterSurfacePass* surfaces = nullptr;
};

class SceneDraws {
 public:
  // `variants`: the scene programs (scene.vert, scene.frag) with the scene's defines.
  SceneDraws(GpuScene& gpu, const SceneDesc& scene, std::unique_ptr<ShaderVariants> variants, SceneStats* stats);

  // Everything the scene will draw, built now, so that the first frame costs no
  // compile and --describe can list exactly what exists: with depth-only variants
  // where `shadows` are cast, without the far sun map where it is `farSun`. The
  // deferrable character primitives are grouped in `surfaces`, which is dropped
  // where it is left without work (CharacterSurfacePass::finishGroups).
  Status buildVariants(bool shadows, bool farSun, std::unique_ptr<CharacterSurfacePass>& surfaces);
  // Once every pass is made.
  void link(const DrawSources& sources) { sources_ = sources; }
  ShaderVariants& variants() { return *variants_; }
  const ShaderVariants& variants() const { return *variants_; }

  // One view's items, culled to `planes` (null: every one), without shape
  // `skipShape`; shadow passes draw the depth-only programs and take no BLEND
  // primitive. `surfaces`: deferrable character primitives go to
  // DrawLists::surface (the main view, where the characters are deferred).
  Result<DrawLists> collect(const glm::dvec4* planes, bool depthOnly, int skipShape = -1, bool surfaces = false);
  // The items in order, in the pass state the caller set, with GPU culling's
  // commands where given.
  Status draw(const std::vector<DrawItem>& items, const PassInputs& pass, const ItemCommands* commands = nullptr);
  // A scene program's uniforms for the frame's shadow maps.
  void setUniforms(const gl::Program& program) const;

 private:
  Status collectShapes(const glm::dvec4* planes, bool depthOnly, int skipShape, DrawLists& lists);
  // `surfaces`: the deferred characters' groups, where this view defers them.
  Status collectCharacters(const glm::dvec4* planes, bool depthOnly, const CharacterSurfacePass* surfaces,
                           DrawLists& lists);
  ShaderVariant shapeVariant(const ShapeDraw& shape, bool depthOnly, bool nearSunOnly) const;
  bool nearSunCovers(const glm::dvec3& lo, const glm::dvec3& hi) const;
  bool characterNearSunOnly(const CharacterDraw& c) const;
  Status submit(const std::vector<DrawItem>& items, const PassInputs& pass, const ItemCommands* commands);
  void drawShape(const ShapeDraw& shape, const gl::Program& program, const PassInputs& pass,
                 const IndirectDraw* indirect);

  GpuScene& gpu_;
  const SceneDesc& scene_;
  std::unique_ptr<ShaderVariants> variants_;
  SceneStats* stats_;
  DrawSources sources_;
};

}  // namespace engine
