#include "render/scene_draws.h"

#include <algorithm>
#include <chrono>
#include <span>

#include "gl/bindings.h"
#include "render/gpu_scene.h"
#include "render/material_uniforms.h"
#include "render/scene_stats.h"
#include "render/surface_groups.h"
#include "scene/scene.h"

namespace engine {
namespace {

// A colour pass hands its draws to llvmpipe's threads (glFlush) each time this
// many triangles have been submitted (at full detail). Fifty CesiumMan of 4,672
// triangles, medians of six alternated runs in a busy hour: unflushed 25.4 ms a
// frame; flushed after every draw 24.8, every second 23.1, every third 22.0.
constexpr std::size_t kFlushTriangles = 12288;

bool sphereVisible(const glm::dvec4 planes[6], const glm::dvec3& center, double radius) {
  if (radius < 0.0) return true;
  for (int i = 0; i < 6; ++i) {
    if (glm::dot(glm::dvec3(planes[i]), center) + planes[i].w < -radius) return false;
  }
  return true;
}

}  // namespace

SceneDraws::SceneDraws(GpuScene& gpu, const SceneDesc& scene, std::unique_ptr<ShaderVariants> variants,
                       SceneStats* stats)
    : gpu_(gpu), scene_(scene), variants_(std::move(variants)), stats_(stats) {}

Status SceneDraws::buildVariants(bool shadows, bool farSun, SurfaceGroups* surfaces) {
  std::vector<ShaderVariant> needed, surfacePasses;
  for (const ShapeDraw& s : gpu_.shapes())
    needed.push_back({0, SkinMode::Linear, gpu_.materialTexture(s.material).id() != 0, false});
  for (const CharacterDraw& c : gpu_.characters()) {
    const ModelData& model = c.instance->asset().model;
    const SkinMode mode = skinModeOf(c.desc);
    const bool cached = c.instance->skinCache() != nullptr;
    // Deforms the first pose, which builds the skin cache's compute programs too.
    if (auto s = c.instance->prepare(mode); !s) return s;
    for (const NodeData& node : model.nodes) {
      if (node.mesh < 0) continue;
      for (const PrimitiveData& prim : model.meshes[size_t(node.mesh)].primitives) {
        const ShaderVariant forward = primitiveVariant(model, node, prim, mode, false, cached);
        needed.push_back(forward);
        const bool blend = c.instance->asset().gpu.material(prim.material).blends();
        if (surfaces && !blend && forward.deferrable()) {
          surfaces->add(c.instance->asset(), prim.material, forward);
          surfacePasses.push_back(forward);
          surfacePasses.back().surface = ShaderVariant::Surface::Out;
        }
        if (shadows && !blend) needed.push_back(primitiveVariant(model, node, prim, mode, true, cached));
      }
    }
  }
  if (shadows && !gpu_.shapes().empty()) needed.push_back({0, SkinMode::Linear, false, true});
  if (surfaces) surfaces->finish(surfacePasses, needed);
  // Each colour program also without the far sun map, for draws the near map
  // covers (ShaderVariant::nearSunOnly; which ones depends on the camera).
  for (std::size_t i = 0, n = needed.size(); i < n && farSun; ++i) {
    if (needed[i].depthOnly || needed[i].surface != ShaderVariant::Surface::None) continue;
    ShaderVariant nearOnly = needed[i];
    nearOnly.nearSunOnly = true;
    needed.push_back(nearOnly);
  }
  for (const ShaderVariant& v : needed) {
    auto program = variants_->get(v);
    if (!program) return program.error();
  }
  return Ok{};
}

void SceneDraws::setUniforms(const gl::Program& program) const {
  if (sources_.shadowUniforms) sources_.shadowUniforms(program);
}

// A shape's program: textured where its material has a texture, matte where it has
// no highlight.
ShaderVariant SceneDraws::shapeVariant(const ShapeDraw& shape, bool depthOnly, bool nearSunOnly) const {
  ShaderVariant v{0, SkinMode::Linear, !depthOnly && gpu_.materialTexture(shape.material).id() != 0, depthOnly};
  v.matte = gpu_.source().materials()[size_t(shape.material)].surface.specular <= 0.0f;
  v.oneSided = !shape.twoSided;
  v.nearSunOnly = nearSunOnly;
  return v;
}

bool SceneDraws::nearSunCovers(const glm::dvec3& lo, const glm::dvec3& hi) const {
  return sources_.nearSunCovers && sources_.nearSunCovers(lo, hi);
}

// The near sun map covers the character's placed bounding sphere.
bool SceneDraws::characterNearSunOnly(const CharacterDraw& c) const {
  const auto [center, r] = gpu_.placedSphere(c);
  return nearSunCovers(center - r, center + r);
}

// The scene's shapes for one view: culled, each with its program (shadow passes
// draw the depth-only one), keyed by program, material and distance.
Status SceneDraws::collectShapes(const glm::dvec4* planes, bool depthOnly, int skipShape, DrawLists& lists) {
  for (int index = 0; index < int(gpu_.shapes().size()); ++index) {
    const ShapeDraw& s = gpu_.shapes()[size_t(index)];
    if (index == skipShape) continue;
    const glm::dvec3 center = s.center - gpu_.eye();
    if (planes && !sphereVisible(planes, center, s.radius)) {
      ++stats_->objectsCulled;
      continue;
    }
    ++stats_->objectsDrawn;
    const bool nearSunOnly = !depthOnly && nearSunCovers(s.lo - gpu_.eye(), s.hi - gpu_.eye());
    auto program = variants_->get(shapeVariant(s, depthOnly, nearSunOnly));
    if (!program) return program.error();
    const GLuint id = (*program)->id();
    const double distance = s.radius < 0.0 ? 0.0 : glm::length(center);
    lists.opaque.push_back(
        {DrawItem::Source::Shape, index, -1, -1, id, opaqueKey(id, std::uint32_t(s.material), distance), -1, nearSunOnly});
  }
  return Ok{};
}

// Every primitive of every visible character: opaque and MASK ones keyed like
// shapes (materials after the scene's own), BLEND ones back to front by the centre
// of their bounds (whole primitives, so intersecting panes can still be out of
// order). Shadow passes take no BLEND primitive: a tinted pane in a depth map
// would be an opaque sheet.
Status SceneDraws::collectCharacters(const glm::dvec4* planes, bool depthOnly, const SurfaceGroups* surfaces,
                                     DrawLists& lists) {
  for (int index = 0; index < int(gpu_.characters().size()); ++index) {
    const CharacterDraw& c = gpu_.characters()[size_t(index)];
    const glm::dvec3 center = glm::dvec3(c.world * glm::dvec4(c.localCenter, 1.0)) - gpu_.eye();
    if (planes && !sphereVisible(planes, center, c.localRadius)) {
      ++stats_->objectsCulled;
      continue;
    }
    ++stats_->objectsDrawn;
    const ModelData& model = c.instance->asset().model;
    const SkinMode mode = skinModeOf(c.desc);
    const bool cached = c.instance->skinCache() != nullptr;
    const bool nearSunOnly = !depthOnly && characterNearSunOnly(c);
    const double distance = glm::length(center);
    for (int n = 0; n < int(model.nodes.size()); ++n) {
      const NodeData& node = model.nodes[size_t(n)];
      if (node.mesh < 0) continue;
      const auto& prims = model.meshes[size_t(node.mesh)].primitives;
      for (int p = 0; p < int(prims.size()); ++p) {
        const PrimitiveData& prim = prims[size_t(p)];
        const bool blend = c.instance->asset().gpu.material(prim.material).blends();
        if (blend && depthOnly) continue;
        ShaderVariant variant = primitiveVariant(model, node, prim, mode, depthOnly, cached);
        variant.nearSunOnly = nearSunOnly;
        const int group = surfaces && !blend && variant.deferrable()
                              ? surfaces->groupOf(c.instance->asset(), prim.material, variant)
                              : -1;
        const bool surface = group >= 0;
        if (surface) variant.surface = ShaderVariant::Surface::Out;
        auto program = variants_->get(variant);
        if (!program) return program.error();
        const GLuint id = (*program)->id();
        const bool transmissive =
            !depthOnly && c.instance->asset().gpu.material(prim.material).transmissive();
        lists.refracts = lists.refracts || transmissive;
        if (!blend) {
          const std::uint32_t material = std::uint32_t(scene_.materials.size()) + std::uint32_t(std::max(prim.material, 0));
          (surface ? lists.surface : transmissive ? lists.transmissive : lists.opaque)
              .push_back({DrawItem::Source::Character, index, n, p, id, opaqueKey(id, material, distance), group,
                          variant.nearSunOnly});
        }
      }
    }
    if (depthOnly) continue;
    for (const BlendPrimitive& b : c.instance->blendPrimitives()) {
      const NodeData& node = model.nodes[size_t(b.node)];
      ShaderVariant variant = primitiveVariant(model, node, model.meshes[size_t(node.mesh)].primitives[size_t(b.primitive)],
                                               mode, false, cached);
      variant.nearSunOnly = nearSunOnly;
      auto program = variants_->get(variant);
      if (!program) return program.error();
      lists.blend.push_back(
          {DrawItem::Source::Character, index, b.node, b.primitive, (*program)->id(), blendKey(b.distance), -1, nearSunOnly});
    }
  }
  return Ok{};
}

Result<DrawLists> SceneDraws::collect(const glm::dvec4* planes, bool depthOnly, int skipShape, bool surfaces) {
  const auto start = std::chrono::steady_clock::now();
  DrawLists lists;
  if (auto s = collectShapes(planes, depthOnly, skipShape, lists); !s) return s.error();
  const SurfaceGroups* grouping = surfaces ? sources_.surfaces : nullptr;
  if (auto s = collectCharacters(planes, depthOnly, grouping, lists); !s) return s.error();
  sortDrawItems(lists.opaque);
  sortDrawItems(lists.surface);
  sortDrawItems(lists.transmissive);
  sortDrawItems(lists.blend);
  stats_->cullMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return lists;
}

void SceneDraws::drawShape(const ShapeDraw& s, const gl::Program& p, const PassInputs& pass,
                           const IndirectDraw* indirect) {
  // The scene layer's table (scene/materials.h): the tracers shade the shape with it too.
  const SceneMaterial& m = gpu_.source().materials()[size_t(s.material)];
  const glm::mat4 model = gpu_.shapeModel(s);
  p.set("u_model", model);
  p.set("u_normalMatrix", glm::mat3(glm::transpose(glm::inverse(glm::mat3(model)))));
  p.set("u_uvScale", s.uvScale * (gpu_.isQuad(s.mesh) ? 1.0f : m.surface.textureScale));
  if (pass.depthOnly) {
    p.set("u_lightViewProjection", pass.lightViewProjection);
  } else {
    forEachSurfaceUniform(m, [&](const char* name, const auto& value) { p.set(name, value); });
    if (gpu_.materialTexture(s.material).id() != 0) gpu_.materialTexture(s.material).bind(gl::binding::kBaseColor);
    if (sources_.probeCube) {
      const bool probed = pass.useProbes && s.probe >= 0;
      p.set("u_hasProbe", probed ? 1 : 0);
      if (probed) sources_.probeCube(s.probe).bind(gl::binding::kReflectionProbe);
    }
  }
  // Two-sided: no culling for this draw, and the pass's setting put back (the
  // point light's cube pass culls nothing: turning culling on after the ground
  // would cull every caster drawn after it, as the sort order falls).
  const bool twoSided = s.twoSided && glIsEnabled(GL_CULL_FACE);
  if (twoSided) glDisable(GL_CULL_FACE);
  if (indirect) {
    s.mesh->drawIndirect(indirect->offset, indirect->count);
  } else {
    s.mesh->draw();
  }
  if (twoSided) glEnable(GL_CULL_FACE);
}

// The items in order, in the pass state the caller set. A program's pass-wide
// uniforms (shadow parameters) are set when the pass first binds it, and each
// change of program is counted: sorting keeps the count near the number of
// programs the view needs.
Status SceneDraws::draw(const std::vector<DrawItem>& items, const PassInputs& pass, const ItemCommands* commands) {
  const auto start = std::chrono::steady_clock::now();
  const Status status = submit(items, pass, commands);
  stats_->submitMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return status;
}

Status SceneDraws::submit(const std::vector<DrawItem>& items, const PassInputs& pass, const ItemCommands* commands) {
  std::vector<std::uint32_t> programs;
  for (const DrawItem& item : items) programs.push_back(item.program);
  std::sort(programs.begin(), programs.end());
  stats_->programsNeeded += int(std::unique(programs.begin(), programs.end()) - programs.begin());
  GLuint bound = 0;
  auto set = [&](const gl::Program& p) {
    if (p.id() == bound) return;
    bound = p.id();
    ++stats_->programChanges;
    // A depth pass's programs read no shadow map (they write one).
    if (pass.depthOnly) {
      p.set("u_lightViewProjection", pass.lightViewProjection);
    } else {
      setUniforms(p);
    }
  };
  std::size_t pending = 0;  // triangles submitted since the last flush
  for (std::size_t k = 0; k < items.size(); ++k) {
    const DrawItem& item = items[k];
    // llvmpipe's threads shade what a flush hands them while this thread goes on
    // with the next draws' vertices; unflushed, a pass's fragments wait for the
    // frame's end. Depth passes are cheap to shade, and keep one batch.
    if (!pass.depthOnly && pending >= kFlushTriangles) {
      glFlush();
      pending = 0;
    }
    pending += gpu_.triangles(item);
    const std::span<const IndirectDraw> indirect =
        commands ? std::span<const IndirectDraw>((*commands)[k]) : std::span<const IndirectDraw>();
    ++stats_->drawCalls;
    if (item.source == DrawItem::Source::Shape) {
      const ShapeDraw& shape = gpu_.shapes()[size_t(item.object)];
      auto program = variants_->get(shapeVariant(shape, pass.depthOnly, item.nearSunOnly));
      if (!program) return program.error();
      (*program)->use();
      set(**program);
      drawShape(shape, **program, pass, indirect.empty() ? nullptr : &indirect[0]);
      continue;
    }
    CharacterDraw& c = gpu_.characters()[size_t(item.object)];
    CharacterInstance::PrimitivePass how;
    how.depthOnly = pass.depthOnly;
    how.nearSunOnly = item.nearSunOnly;
    how.indirect = indirect;
    if (pass.surface) {
      how.surface = ShaderVariant::Surface::Out;
      if (sources_.surfaces->stencil()) glStencilFunc(GL_ALWAYS, kFirstSurfaceStencil + item.surfaceGroup, 0xff);
    }
    if (auto s = c.instance->drawPrimitive(*variants_, skinModeOf(c.desc), set, item.node,
                                           item.primitive, how);
        !s) {
      return s;
    }
  }
  return Ok{};
}

}  // namespace engine
