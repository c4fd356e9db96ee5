// SceneRenderer's draws: each view's culled, sorted draw items and their
// submission; the world of one view (its opaque draws, the terrain, the sky behind
// them, then transmissive and blended draws) and the reflection probes.
#include <algorithm>

#include "render/scene_renderer_impl.h"
#include "render/sun_coverage.h"

namespace engine {
namespace {

constexpr double kProbeNear = 0.01;
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

void SceneRenderer::Impl::setUniforms(const gl::Program& program) const {
  if (sunShadows) {
    program.set("u_sunTexelWorld", float(sunTexelWorld));
    sunShadowMap.bind(gl::binding::kSunShadow);
    if (sunFarShadows) sunShadowMapFar.bind(gl::binding::kSunShadowFar);
  }
  if (pointShadows) {
    program.set("u_pointNear", float(pointNear));
    pointShadowMap.bind(gl::binding::kPointShadow);
  }
}

void SceneRenderer::Impl::fillFrame(const glm::dvec3& cameraPosition, const glm::mat4& viewProjection) {
  frame.viewProjection = viewProjection;
  frame.sunDirection = glm::vec4(0.0f);
  if (sunLight >= 0) {
    const LightDesc& sun = scene.lights[size_t(sunLight)];
    frame.sunDirection = glm::vec4(glm::vec3(sun.direction), 1.0f);
    frame.sunColor = glm::vec4(sun.color * sun.intensity, 0.0f);
  }
  frame.counts = glm::ivec4(int(pointLights.size()), 0, 0, 0);
  for (size_t i = 0; i < pointLights.size(); ++i) {
    const LightDesc& l = scene.lights[size_t(pointLights[i])];
    frame.pointPosition[i] = glm::vec4(glm::vec3(l.position - cameraPosition), l.falloff ? 1.0f : 0.0f);
    frame.pointColor[i] = glm::vec4(l.color * l.intensity, l.shadows ? 1.0f : 0.0f);
  }
  // Ambient from the sky: the zenith and ground colours, dimmed.
  frame.ambientSky = glm::vec4(ambientSkyColor(scene), scene.ambient);
  frame.ambientGround = glm::vec4(ambientGroundColor(scene), 0.0f);
  frame.fog = scene.fog.enabled ? glm::vec4(scene.fog.color, scene.fog.density) : glm::vec4(0.0f);
  frame.shadowParams = glm::vec4(sunShadowSize ? 1.0f / float(sunShadowSize) : 0.0f, float(pcfRadius),
                                 float(pointFar), cubeSize ? 2.0f / float(cubeSize) : 0.0f);
  if (environmentLighting) {
    for (int i = 0; i < 9; ++i) frame.shIrradiance[i] = glm::vec4(environmentLighting->sh().coefficients[size_t(i)], 0.0f);
    frame.iblParams = glm::vec4(float(environmentLighting->maxLevel()), 0.0f, 0.0f, 0.0f);
    environmentLighting->bind();
  }
  frameUbo.upload(0, sizeof(FrameBlock), &frame);
  glBindBufferBase(GL_UNIFORM_BUFFER, gl::binding::kFrameBlock, frameUbo.id());
}

// A shape's program: textured where its material has a texture, matte where it has
// no highlight.
ShaderVariant SceneRenderer::Impl::shapeVariant(const ShapeDraw& shape, bool depthOnly, bool nearSunOnly) const {
  ShaderVariant v{0, SkinMode::Linear, !depthOnly && gpu->materialTexture(shape.material).id() != 0, depthOnly};
  v.matte = scene.materials[size_t(shape.material)].specular <= 0.0f;
  v.oneSided = !shape.twoSided;
  v.nearSunOnly = nearSunOnly;
  return v;
}

// The far sun map's nine taps run for every fragment of a program that has them
// (llvmpipe runs both sides of an `if`): about 15 CPU ms of demo.json's frame,
// whose shapes and robots all lie where the near map covers.
bool SceneRenderer::Impl::nearSunCovers(const glm::dvec3& lo, const glm::dvec3& hi) const {
  return sunFarShadows && withinNearSunMap(glm::dmat4(frame.sunShadowMatrix), lo, hi, sunTexelWorld);
}

// The near sun map covers the character's placed bounding sphere.
bool SceneRenderer::Impl::characterNearSunOnly(const CharacterDraw& c) const {
  const auto [center, r] = gpu->placedSphere(c);
  return nearSunCovers(center - r, center + r);
}

// The scene's shapes for one view: culled, each with its program (shadow passes
// draw the depth-only one), keyed by program, material and distance.
Status SceneRenderer::Impl::collectShapes(const glm::dvec4* planes, bool depthOnly, int skipShape, DrawLists& lists) {
  for (int index = 0; index < int(gpu->shapes().size()); ++index) {
    const ShapeDraw& s = gpu->shapes()[size_t(index)];
    if (index == skipShape) continue;
    const glm::dvec3 center = s.center - gpu->eye();
    if (planes && !sphereVisible(planes, center, s.radius)) {
      ++stats->objectsCulled;
      continue;
    }
    ++stats->objectsDrawn;
    const bool nearSunOnly = !depthOnly && nearSunCovers(s.lo - gpu->eye(), s.hi - gpu->eye());
    auto program = variants->get(shapeVariant(s, depthOnly, nearSunOnly));
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
Status SceneRenderer::Impl::collectCharacters(const glm::dvec4* planes, bool depthOnly, bool surfaces,
                                              DrawLists& lists) {
  for (int index = 0; index < int(gpu->characters().size()); ++index) {
    const CharacterDraw& c = gpu->characters()[size_t(index)];
    const glm::dvec3 center = glm::dvec3(c.world * glm::dvec4(c.localCenter, 1.0)) - gpu->eye();
    if (planes && !sphereVisible(planes, center, c.localRadius)) {
      ++stats->objectsCulled;
      continue;
    }
    ++stats->objectsDrawn;
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
        const bool blend = prim.material >= 0 && model.materials[size_t(prim.material)].alphaMode == AlphaMode::Blend;
        if (blend && depthOnly) continue;
        ShaderVariant variant = primitiveVariant(model, node, prim, mode, depthOnly, cached);
        variant.nearSunOnly = nearSunOnly;
        const int group = surfaces && !blend && variant.deferrable()
                              ? surfaceGroupOf(c.instance->asset(), prim.material, variant)
                              : -1;
        const bool surface = group >= 0;
        if (surface) variant.surface = ShaderVariant::Surface::Out;
        auto program = variants->get(variant);
        if (!program) return program.error();
        const GLuint id = (*program)->id();
        const bool transmissive =
            !depthOnly && prim.material >= 0 && model.materials[size_t(prim.material)].layers.transmissive();
        lists.refracts = lists.refracts || transmissive;
        if (!blend) {
          const std::uint32_t material = std::uint32_t(scene.materials.size()) + std::uint32_t(std::max(prim.material, 0));
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
      auto program = variants->get(variant);
      if (!program) return program.error();
      lists.blend.push_back(
          {DrawItem::Source::Character, index, b.node, b.primitive, (*program)->id(), blendKey(b.distance), -1, nearSunOnly});
    }
  }
  return Ok{};
}

Result<DrawLists> SceneRenderer::Impl::collectDraws(const glm::dvec4* planes, bool depthOnly, int skipShape,
                                                   bool surfaces) {
  const auto start = std::chrono::steady_clock::now();
  DrawLists lists;
  if (auto s = collectShapes(planes, depthOnly, skipShape, lists); !s) return s.error();
  if (auto s = collectCharacters(planes, depthOnly, surfaces, lists); !s) return s.error();
  sortDrawItems(lists.opaque);
  sortDrawItems(lists.surface);
  sortDrawItems(lists.transmissive);
  sortDrawItems(lists.blend);
  stats->cullMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return lists;
}

void SceneRenderer::Impl::drawShape(const ShapeDraw& s, const gl::Program& p, const PassInputs& pass,
                                    const IndirectDraw* indirect) {
  const MaterialDesc& m = scene.materials[size_t(s.material)];
  const glm::mat4 model = gpu->shapeModel(s);
  p.set("u_model", model);
  p.set("u_normalMatrix", glm::mat3(glm::transpose(glm::inverse(glm::mat3(model)))));
  p.set("u_uvScale", s.uvScale * (gpu->isQuad(s.mesh) ? 1.0f : m.textureScale));
  if (pass.depthOnly) {
    p.set("u_lightViewProjection", pass.lightViewProjection);
  } else {
    p.set("u_baseColorFactor", glm::vec4(m.color, 1.0f));
    p.set("u_metallic", m.metallic);
    p.set("u_roughness", m.roughness);
    p.set("u_ambient", m.ambient);
    p.set("u_diffuse", m.diffuse);
    p.set("u_specular", m.specular);
    p.set("u_shininess", m.shininess);
    p.set("u_reflection", m.reflection);
    p.set("u_emissive", m.emission);
    if (gpu->materialTexture(s.material).id() != 0) gpu->materialTexture(s.material).bind(gl::binding::kBaseColor);
    if (!probes.empty()) {
      const bool probed = pass.useProbes && s.probe >= 0;
      p.set("u_hasProbe", probed ? 1 : 0);
      if (probed) probes[size_t(s.probe)].cube.bind(gl::binding::kReflectionProbe);
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
Status SceneRenderer::Impl::drawItems(const std::vector<DrawItem>& items, const PassInputs& pass,
                                      const ItemCommands* commands) {
  const auto start = std::chrono::steady_clock::now();
  const Status status = submitItems(items, pass, commands);
  stats->submitMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return status;
}

Status SceneRenderer::Impl::submitItems(const std::vector<DrawItem>& items, const PassInputs& pass,
                                        const ItemCommands* commands) {
  std::vector<std::uint32_t> programs;
  for (const DrawItem& item : items) programs.push_back(item.program);
  std::sort(programs.begin(), programs.end());
  stats->programsNeeded += int(std::unique(programs.begin(), programs.end()) - programs.begin());
  GLuint bound = 0;
  auto set = [&](const gl::Program& p) {
    if (p.id() == bound) return;
    bound = p.id();
    ++stats->programChanges;
    setUniforms(p);
    if (pass.depthOnly) p.set("u_lightViewProjection", pass.lightViewProjection);
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
    pending += gpu->triangles(item);
    const std::span<const IndirectDraw> indirect =
        commands ? std::span<const IndirectDraw>((*commands)[k]) : std::span<const IndirectDraw>();
    ++stats->drawCalls;
    if (item.source == DrawItem::Source::Shape) {
      const ShapeDraw& shape = gpu->shapes()[size_t(item.object)];
      auto program = variants->get(shapeVariant(shape, pass.depthOnly, item.nearSunOnly));
      if (!program) return program.error();
      (*program)->use();
      set(**program);
      drawShape(shape, **program, pass, indirect.empty() ? nullptr : &indirect[0]);
      continue;
    }
    CharacterDraw& c = gpu->characters()[size_t(item.object)];
    CharacterInstance::PrimitivePass how;
    how.depthOnly = pass.depthOnly;
    how.nearSunOnly = item.nearSunOnly;
    how.indirect = indirect;
    if (pass.surface) {
      how.surface = ShaderVariant::Surface::Out;
      if (surfaceStencil()) glStencilFunc(GL_ALWAYS, kFirstSurfaceStencil + item.surfaceGroup, 0xff);
    }
    if (auto s = c.instance->drawPrimitive(*variants, pass.viewProjection, skinModeOf(c.desc), set, item.node,
                                           item.primitive, how);
        !s) {
      return s;
    }
  }
  return Ok{};
}

void SceneRenderer::Impl::drawSky(const gl::Program& program, const glm::dmat4& viewProjection, bool sunDisk) {
  program.use();
  if (const gl::Texture& skyImage = gpu->skyImage()) {
    const float radians = glm::radians(scene.sky.rotationDegrees);
    program.set("u_skyIntensity", scene.sky.intensity);
    program.set("u_skyRotation", glm::vec2(std::cos(radians), std::sin(radians)));
    skyImage.bind(gl::binding::kSkyImage);
  } else {
    Lighting lighting;
    lighting.sunDirection = sunLight >= 0 ? glm::vec3(scene.lights[size_t(sunLight)].direction) : glm::vec3(0, -1, 0);
    lighting.sunDisk = sunDisk && sunLight >= 0 && scene.sky.sunDisk;
    lighting.skyZenith = scene.sky.zenith;
    lighting.skyHorizon = scene.sky.horizon;
    lighting.skyGround = scene.sky.ground;
    setSkyUniforms(program, lighting);
  }
  program.set("u_inverseViewProjection", glm::mat4(glm::inverse(viewProjection)));
  emptyVao.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  ++stats->drawCalls;
}

// The sky after the opaque surfaces, where they left the cleared far depth: shaded
// once a pixel instead of under every surface (on demo.json about half the screen),
// the same colour where it shows. Before the transmissive draws, which see it
// through their copy of the frame.
void SceneRenderer::Impl::drawSkyBehind(const View& view) {
  if (!scene.sky.enabled) return;
  applyPassState(kSkyBehindPass);
  drawSky(directOutput ? skyDisplay : sky, view.viewProjection);
}

// Everything a colour pass shows, into the bound HDR framebuffer (cleared): the
// opaque draws of the view, the terrain, the sky where neither is, the transmissive
// draws over a copy of those, then the blended ones.
Status SceneRenderer::Impl::drawWorld(const View& view, int skipShape, bool useProbes) {
  applyPassState(opaquePassFor(view.mirrored));
  auto lists = collectDraws(view.planes, false, skipShape, deferredCharacters && view.main);
  if (!lists) return lists.error();
  if (culler && view.main) return drawCulled(view, *lists, useProbes);
  const PassInputs pass{false, glm::mat4(1.0f), glm::mat4(view.viewProjection), useProbes};
  if (auto s = drawCharacterSurfaces(view, lists->surface, pass, nullptr); !s) return s;
  if (auto s = drawItems(lists->opaque, pass); !s) return s;
  // The terrain after the shapes and characters: its fragment shader (five layers,
  // two sun maps, the ambient) is the frame's dearest, and a plaza or a floor over
  // it then hides what lies beneath before it is shaded (llvmpipe, like any GPU,
  // tests depth before shading). Opaque surfaces keep the nearest depth whatever the
  // order, so the image is the same. drawCulled does the same with its patches
  // culled against the depth of what went before.
  if (terrain) {
    // What is drawn so far goes to the rasterizer now: on llvmpipe its threads then
    // shade the shapes (most of a plaza's pixels) while this thread selects the
    // terrain's patches and bins its triangles, rather than both after it.
    glFlush();
    applyPassState(opaquePassFor(view.mirrored));
    drawTerrain(view, skipShape);
  }
  drawSkyBehind(view);
  if (lists->refracts) {
    if (view.main) copyTransmissionSource();
    transmissionSource.bind(gl::binding::kTransmissionSource);
    applyPassState(opaquePassFor(view.mirrored));
    if (auto s = drawItems(lists->transmissive, pass); !s) return s;
  }
  if (lists->blend.empty()) return Ok{};
  applyPassState(blendPassFor(view.mirrored));
  return drawItems(lists->blend, pass);
}

// The view camera's LOD (its position, field of view and viewport fix every
// patch's level and morph), culled against `cullViewProjection`; coarsened if it
// would need more height pages than the GPU pool holds.
terrain::LodSelection SceneRenderer::Impl::selectTerrain(const glm::mat4& cullViewProjection, double fovy,
                                                         int viewportHeight) const {
  TerrainView view = terrainView(fovy, viewportHeight);
  view.cullViewProjection = cullViewProjection;
  view.zeroToOneDepth = true;  // reverse-Z and the sun's box both clip depth to 0..w
  return engine::selectTerrain(*terrain, view);
}

// Every terrain block error the view from `eye` needs, before any of the frame's
// selections: they all see the same errors, so the sun's maps keep the view's
// ranges; and a frame's image depends on its camera alone, not on which frames came
// before (a window and an offscreen run of another length give the same bytes). A
// new view pays about 2 ms a block, once.
void SceneRenderer::Impl::measureTerrain(double fovy, int viewportHeight) {
  stats->terrainBlocksPending = int(engine::measureTerrain(*terrain, terrainView(fovy, viewportHeight)));
  stats->terrainViewportHeight = viewportHeight;
}

// The scene layer's terrain view (scene/terrain_mesh.h) from `eye`: the tracers
// select theirs through the same function with the same target and page budget.
TerrainView SceneRenderer::Impl::terrainView(double fovy, int viewportHeight) const {
  TerrainView view;
  view.eye = gpu->eye();
  view.fovY = fovy;
  view.viewportHeight = viewportHeight;
  view.errorPixels = terrainError;
  view.maxPages = std::size_t(terrainRenderer->pageSlots());
  return view;
}

void SceneRenderer::Impl::drawTerrain(const View& view, int skipShape) {
  auto selection = selectTerrain(glm::mat4(view.viewProjection), view.fovy, view.height);
  hidePatchesBehindPlanes(selection, view, skipShape);
  const terrain::TerrainOutput output = beginTerrainSurface(view);
  const auto drawn =
      terrainRenderer->draw(selection, gpu->eye(), [this](const gl::Program& p) { setUniforms(p); }, output);
  stats->drawCalls += 1;
  stats->terrainTriangles = int(drawn.trianglesDrawn);
  shadeTerrainSurface(view, selection);
  if (view.main) mainTerrain = std::move(selection);
}

// The main view's terrain, without MSAA, is shaded once a pixel: llvmpipe shades
// eight lanes at a time, and the far patches' triangles cover a pixel or two each,
// so shading where they are drawn pays several times a pixel (about 12 ms of
// demo.json's frame). Their surface goes into drawFbo's second attachment instead,
// where the terrain is nearest so far, marked in the stencil; shadeTerrainSurface
// then shades those pixels with the same lighting. Texture levels of detail come
// from the surface pass, where each triangle's own derivatives are known. Returns
// what the terrain's draws write: the surface, or (elsewhere) the colour.
terrain::TerrainOutput SceneRenderer::Impl::beginTerrainSurface(const View& view) {
  if (!deferredTerrain || !view.main) return terrain::TerrainOutput::Colour;
  const GLenum surfaceOnly[] = {GL_COLOR_ATTACHMENT1};  // terrain.frag's output 0
  glNamedFramebufferDrawBuffers(drawFbo.id(), 1, surfaceOnly);
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_ALWAYS, kTerrainStencil, 0xff);
  glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
  return terrain::TerrainOutput::Surface;
}

// After beginTerrainSurface's draws: a full-screen pass where the stencil marks
// terrain. A no-op where the terrain was shaded where drawn.
void SceneRenderer::Impl::shadeTerrainSurface(const View& view, const terrain::LodSelection& selection) {
  if (!deferredTerrain || !view.main) return;
  const GLenum colourOnly[] = {GL_COLOR_ATTACHMENT0};
  glNamedFramebufferDrawBuffers(drawFbo.id(), 1, colourOnly);
  applyPassState(kSurfaceShadingPass);
  glStencilFunc(GL_EQUAL, kTerrainStencil, 0xff);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  terrainRenderer->shadeDeferred(selection, gpu->eye(), glm::mat4(glm::inverse(view.viewProjection)),
                                 [this](const gl::Program& p) {
                                   setUniforms(p);
                                   terrainSurface.bind(gl::binding::kTerrainSurface);
                                 });
  stats->drawCalls += 1;
  glDisable(GL_STENCIL_TEST);
}

// The selection's patches that one of the view's opaque planes hides wholly
// (render/plane_occlusion.h), left out: the image is the same, less the cost of
// rasterizing what would fail the depth test everywhere. `skipShape` (a probe's
// own mirror) is not drawn in the view, so it hides nothing.
void SceneRenderer::Impl::hidePatchesBehindPlanes(terrain::LodSelection& selection, const View& view,
                                                  int skipShape) const {
  if (!planeOcclusion) return;
  const glm::dvec2 viewport(view.width, view.height);
  const auto quads = cull::opaquePlanes(scene, gpu->eye(), view.viewProjection, viewport, skipShape);
  stats->terrainPatchesHidden +=
      int(removeHiddenPatches(*terrain, selection, quads, view.viewProjection, viewport, planeOcclusionPixelMargin));
}

// What the transmissive draws refract: the view's colour so far (sky, terrain and
// opaque draws; MSAA resolved by the blit), with its mip chain for rough surfaces.
void SceneRenderer::Impl::copyTransmissionSource() {
  glBlitNamedFramebuffer(drawFbo.id(), transmissionFbo.id(), 0, 0, targetWidth, targetHeight, 0, 0, targetWidth,
                         targetHeight, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glGenerateTextureMipmap(transmissionSource.id());
}

// Each probe's six faces, seen from the mirror's centre without the mirror itself.
// Positions stay camera-relative, now to the probe's centre. The sun's maps are
// drawn again around the probe: the camera's maps cover what the camera sees, and
// a static scene keeps its probes however far the camera then goes. Probes show no
// mirrors: one bounce, where the ray tracer follows --max-depth bounces. Before the
// camera's own sun maps, which this overwrites.
Status SceneRenderer::Impl::renderProbes(const glm::dvec3& cameraPosition) {
  const glm::dmat4 projection = reverseZProjection(glm::half_pi<double>(), 1.0, kProbeNear, scene.camera.farPlane);
  const glm::vec3 background = scene.sky.background;
  for (const Probe& probe : probes) {
    gpu->place(probe.center);
    if (sunShadows) {
      // All around the probe, as far as the camera's maps reach ahead of it.
      const ShadowSphere nearSphere{glm::dvec3(0.0), std::min(scene.camera.farPlane, kSunShadowDistance)};
      const ShadowSphere farSphere{glm::dvec3(0.0), std::min(scene.camera.farPlane, kSunFarShadowDistance)};
      if (auto s = renderSunShadow(nearSphere, farSphere, glm::half_pi<double>(), probeSize); !s) return s;
    }
    glViewport(0, 0, probeSize, probeSize);
    for (int face = 0; face < 6; ++face) {
      View view;
      view.viewProjection = projection * glm::lookAt(glm::dvec3(0.0), kCubeFaceDirections[face], kCubeFaceUps[face]);
      frustumPlanes(view.viewProjection, view.planes);
      view.fovy = glm::half_pi<double>();
      view.width = view.height = probeSize;
      fillFrame(probe.center, glm::mat4(view.viewProjection));
      glNamedFramebufferTextureLayer(probeFbo.id(), GL_COLOR_ATTACHMENT0, probe.cube.id(), 0, face);
      probeFbo.bind();
      applyPassState(opaquePassFor(false));  // depth writes on, for the clear
      glClearColor(background.r, background.g, background.b, 1.0f);
      glClearDepth(0.0);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      if (auto s = drawWorld(view, probe.shape, false); !s) return s;
    }
  }
  gpu->place(cameraPosition);
  return Ok{};
}

}  // namespace engine
