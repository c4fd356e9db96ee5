#pragma once
// Each view's draw items (render/draw_items.h): the GPU scene's shapes and
// character primitives culled to the view, each with its program, sorted; and
// their submission in the pass state the caller set. Every pass draws through it;
// it owns the scene programs' shader variants, all built at load. Not part of the
// engine's interface.
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "asset/scene_desc.h"
#include "core/result.h"
#include "gl/resources.h"
#include "render/model_renderer.h"
#include "render/scene_view.h"

namespace engine {

class GpuScene;
class SurfaceGroups;
struct SceneStats;
struct ShapeDraw;
struct CharacterDraw;

// What the draws read of other passes' results, where the scene has them (each
// empty otherwise): the shadow maps' uniforms every lit program samples (the sun's,
// then the point light's), whether the near sun map covers a box, the probes' cubes
// that mirrors show, the deferred characters' groups. Functions the renderer binds
// to its passes, not the passes: each pass draws through SceneDraws, which
// therefore includes none of them.
struct DrawSources {
  std::function<void(const gl::Program&)> shadowUniforms;
  std::function<bool(const glm::dvec3& lo, const glm::dvec3& hi)> nearSunCovers;
  std::function<const gl::Texture&(int probe)> probeCube;
  const SurfaceGroups* surfaces = nullptr;
};

class SceneDraws {
 public:
  // `variants`: the scene programs (scene.vert, scene.frag) with the scene's defines.
  SceneDraws(GpuScene& gpu, const SceneDesc& scene, std::unique_ptr<ShaderVariants> variants, SceneStats* stats);

  // Everything the scene will draw, built now, so that the first frame costs no
  // compile and --describe can list exactly what exists: with depth-only variants
  // where `shadows` are cast, without the far sun map where it is `farSun`. The
  // deferrable character primitives are grouped in `surfaces` (left empty where
  // there is no work for the deferred pass: SurfaceGroups::finish).
  Status buildVariants(bool shadows, bool farSun, SurfaceGroups* surfaces);
  // Once every pass is made.
  void link(DrawSources sources) { sources_ = std::move(sources); }
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
  Status collectCharacters(const glm::dvec4* planes, bool depthOnly, const SurfaceGroups* surfaces,
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
