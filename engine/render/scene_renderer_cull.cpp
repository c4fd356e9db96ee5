// SceneRenderer with GPU culling (render.gpu_culling): the jobs of each view's
// draw items, the Hi-Z occluder pyramid, and the indirect draws it leaves.
#include "render/scene_renderer_impl.h"

#include <algorithm>
#include <chrono>
#include <iterator>

#include "gl/bindings.h"
#include "render/pass_state.h"
#include "render/terrain_cull.h"

namespace engine {

// GPU culling's programs and cluster table: every shape mesh's and every model
// primitive's clusters (made when they were uploaded), once per mesh.
Status SceneRenderer::Impl::makeCuller() {
  if (!render.gpuCulling) return Ok{};
  auto made = GpuCuller::create(shaderDir);
  if (!made) return makeError(scene.path + ": /render/gpu_culling: " + made.error().message);
  culler = std::make_unique<GpuCuller>(std::move(made).value());
  if (terrain) {
    auto forTerrain = GpuCuller::create(shaderDir);
    if (!forTerrain) return makeError(scene.path + ": /render/gpu_culling: " + forTerrain.error().message);
    terrainCuller = std::make_unique<GpuCuller>(std::move(forTerrain).value());
  }
  auto pyramid = HiZPyramid::create(shaderDir, depthFormat());
  if (!pyramid) return makeError(scene.path + ": /render/gpu_culling: " + pyramid.error().message);
  hiz = std::make_unique<HiZPyramid>(std::move(pyramid).value());
  for (const GpuMesh* mesh : gpu->meshes()) shapeClusterBase[mesh] = culler->addClusters(mesh->clusters());
  for (const CharacterDraw& c : gpu->characters())
    for (const auto& mesh : c.instance->asset().gpu.meshes())
      for (const GpuPrimitive& p : mesh)
        if (!p.clusters.empty() && !primitiveClusterBase.count(&p)) primitiveClusterBase[&p] = culler->addClusters(p.clusters);
  return Ok{};
}

// A shape's job: its own matrix and clusters, its bounding sphere (none for a plane).
std::vector<IndirectDraw> SceneRenderer::Impl::queueShapeJob(const ShapeDraw& s) {
  cull::Job job;
  job.model = gpu->shapeModel(s);
  job.sphere = s.radius < 0.0 ? glm::vec4(0.0f, 0.0f, 0.0f, -1.0f) : glm::vec4(glm::vec3(s.center - gpu->eye()), float(s.radius));
  const cull::ClusterRange range = s.mesh->clusterRange();
  job.firstCluster = shapeClusterBase.at(s.mesh) + range.first;
  job.clusterCount = range.count;
  return {culler->commandsOf(culler->addJob(job))};
}

// A character primitive's jobs, one per mesh instance, in the order drawPrimitive
// draws them: the clusters of the level of detail it will draw, the character's
// bounding sphere (of every pose: the bounds collectCharacters culls by). A
// skinned or morphed primitive's vertices move away from the rest positions its
// clusters were bounded by, so only its sphere is tested (cull::kInstanceOnly).
std::vector<IndirectDraw> SceneRenderer::Impl::queueCharacterJobs(const DrawItem& item) {
  const CharacterDraw& c = gpu->characters()[size_t(item.object)];
  const ModelData& model = c.instance->asset().model;
  const NodeData& node = model.nodes[size_t(item.node)];
  const GpuPrimitive& prim = c.instance->asset().gpu.meshes()[size_t(node.mesh)][size_t(item.primitive)];
  const PrimitiveData& data = model.meshes[size_t(node.mesh)].primitives[size_t(item.primitive)];
  if (!hasClusters(prim, data.mode)) return {};
  const SkinMode mode = skinModeOf(c.desc);
  const int level = levelIndexWithin(prim, c.instance->lodBudget());
  const cull::ClusterRange range = level < 0 ? prim.fullClusters : prim.levels[size_t(level)].clusters;
  cull::Job job;
  const glm::dvec3 center = glm::dvec3(c.world * glm::dvec4(c.localCenter, 1.0)) - gpu->eye();
  job.sphere = glm::vec4(glm::vec3(center), float(c.localRadius));
  job.firstCluster = primitiveClusterBase.at(&prim) + range.first;
  job.clusterCount = range.count;
  job.flags = skinnedBy(node, data.influences, mode) || data.morphTargets > 0 ? cull::kInstanceOnly : 0u;
  std::vector<IndirectDraw> out;
  for (const glm::mat4& m : c.instance->instanceModels(mode, item.node, data.influences)) {
    job.model = m;
    out.push_back(culler->commandsOf(culler->addJob(job)));
  }
  return out;
}

ItemCommands SceneRenderer::Impl::queueJobs(const std::vector<DrawItem>& items) {
  ItemCommands out;
  out.reserve(items.size());
  for (const DrawItem& item : items) {
    out.push_back(item.source == DrawItem::Source::Shape ? queueShapeJob(gpu->shapes()[size_t(item.object)])
                                                         : queueCharacterJobs(item));
  }
  return out;
}

// Culls jobs [firstJob, endJob) for the main view: against a pyramid of the depth
// drawn into the bound framebuffer so far, or the frustum alone. The depth only
// ever comes nearer during the view's pass (GL_GREATER, no clears), so what it
// hides now stays hidden for the rest of the pass.
void SceneRenderer::Impl::cullPhase(GpuCuller& with, std::size_t firstJob, std::size_t endJob, const View& view,
                                    bool occlusion) {
  if (endJob <= firstJob) return;
  // The pyramid needs the depth drawn so far, which llvmpipe rasterises only when
  // flushed: waited for here, so that the time below is the culling's own.
  if (occlusion) glFinish();
  const auto start = std::chrono::steady_clock::now();
  if (occlusion) {
    GLint framebuffer = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    hiz->build(GLuint(framebuffer), targetWidth, targetHeight);
  }
  with.cull(firstJob, endJob, glm::mat4(view.viewProjection), occlusion ? hiz.get() : nullptr, cullDepthMargin);
  ++stats->cullDispatches;
  stats->gpuCullMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Whether an opaque item can stand in the occluder prepass: a shape, or a model
// primitive that neither deforms (the prepass would need its skinning) nor cuts
// holes (MASK); either way one drawn in this very pass, so the depth it leaves in
// the prepass is depth the pass's own depth buffer will hold.
bool SceneRenderer::Impl::isOccluder(const DrawItem& item) const {
  if (item.source == DrawItem::Source::Shape) return true;
  const CharacterDraw& c = gpu->characters()[size_t(item.object)];
  const ModelData& model = c.instance->asset().model;
  const NodeData& node = model.nodes[size_t(item.node)];
  const PrimitiveData& data = model.meshes[size_t(node.mesh)].primitives[size_t(item.primitive)];
  const MaterialData* material = data.material >= 0 ? &model.materials[size_t(data.material)] : nullptr;
  return !skinnedBy(node, data.influences, skinModeOf(c.desc)) && data.morphTargets == 0 &&
         !(material && material->alphaMode != AlphaMode::Opaque);
}

// The pyramid the main view's draws are culled against: the depth drawn so far
// (none but the cleared far plane: the sky writes none, the terrain comes after),
// and the occluders' depth drawn over a copy of it, depth only
// (the occluder prepass). Why that is safe though the occluders come later in the
// pass: an item whose every pixel has, in the end, a strictly nearer depth is
// never the nearest fragment anywhere, and with GL_GREATER the image and the
// depth are the first nearest fragment's; removing a fragment that is not the
// nearest changes neither. Every occluder is an opaque draw of this pass, and the
// pass's final depth is at least the prepass's (up to float rounding between two
// programs' vertex shaders, far inside cull::kDepthMargin). Without occluders
// there is nothing to cull by depth: the frustum only.
Status SceneRenderer::Impl::buildOccluderPyramid(const View& view, const std::vector<DrawItem>& occluders) {
  GLint framebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
  hiz->copyDepth(GLuint(framebuffer), targetWidth, targetHeight);
  Status drawn = Ok{};
  if (!occluders.empty()) {
    glBindFramebuffer(GL_FRAMEBUFFER, hiz->depthFramebuffer());
    const glm::mat4 viewProjection(view.viewProjection);
    drawn = draws->draw(occluders, {true, viewProjection, viewProjection, false});
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(framebuffer));
  }
  hiz->reduce();
  return drawn;
}

// The main view's draws with GPU culling, in the order drawWorld draws them, every
// one culled in one dispatch against the occluder pyramid (above). A window's
// frames and a single offscreen frame cull alike: the pyramid is this frame's own,
// never the last frame's. MSAA, or no occluder: the frustum only
// (MSAA's pyramid would need every sample's depth).
Status SceneRenderer::Impl::drawCulled(const View& view, const DrawLists& lists, bool useProbes) {
  culler->clearJobs();
  const ItemCommands opaqueCommands = queueJobs(lists.opaque);
  const ItemCommands surfaceCommands = queueJobs(lists.surface);
  const ItemCommands transmissiveCommands = queueJobs(lists.transmissive);
  const ItemCommands blendCommands = queueJobs(lists.blend);
  culler->upload();
  std::vector<DrawItem> occluders;
  std::copy_if(lists.opaque.begin(), lists.opaque.end(), std::back_inserter(occluders),
               [this](const DrawItem& item) { return isOccluder(item); });
  const bool occlusion = render.msaa <= 1 && !occluders.empty();
  // The occluders' depth waits for what is drawn before it: timed from there.
  if (occlusion) glFinish();
  const auto start = std::chrono::steady_clock::now();
  if (occlusion) {
    if (auto s = buildOccluderPyramid(view, occluders); !s) return s;
    applyPassState(opaquePassFor(view.mirrored));
  }
  culler->cull(0, culler->jobCount(), glm::mat4(view.viewProjection), occlusion ? hiz.get() : nullptr, cullDepthMargin);
  ++stats->cullDispatches;
  stats->gpuCullMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const PassInputs pass{false, glm::mat4(1.0f), glm::mat4(view.viewProjection), useProbes};
  Status status = surfaces ? surfaces->draw(view, lists.surface, pass, &surfaceCommands, drawFbo) : Status(Ok{});
  if (status) status = draws->draw(lists.opaque, pass, &opaqueCommands);
  // The terrain after the opaque items, as drawWorld draws it: its patches then
  // meet their depth (a plaza over a valley) in the pyramid of its second half.
  if (status && terrain && terrainCuller) {
    applyPassState(opaquePassFor(view.mirrored));
    drawTerrainCulled(view);
    culler->bindCommands();
  }
  if (status) drawSkyBehind(view);
  if (status && lists.refracts) {
    copyTransmissionSource();
    transmissionSource.bind(gl::binding::kTransmissionSource);
    applyPassState(opaquePassFor(view.mirrored));
    status = draws->draw(lists.transmissive, pass, &transmissiveCommands);
  }
  if (status && !lists.blend.empty()) {
    applyPassState(blendPassFor(view.mirrored));
    status = draws->draw(lists.blend, pass, &blendCommands);
  }
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  return status;
}

// The boxes of the terrain's drawn patches (terrainPatchBox): the terrain
// culler's clusters, one a patch.
std::vector<cull::Cluster> SceneRenderer::Impl::terrainPatchBoxes(const terrain::LodSelection& selection) const {
  std::vector<cull::Cluster> out;
  const auto count = std::uint32_t(terrain::TerrainRenderer::indexCount());
  for (const terrain::LodPatch& p : terrain->renderer().patches())
    out.push_back(terrainPatchBox(terrain->terrain(), selection, p, count));
  return out;
}

// The main view's terrain with GPU culling, after the opaque draws: its selection
// (CPU-culled to the frustum by the CDLOD traversal, as without) in two halves of
// the drawing order, the first culled against the frustum alone, the second
// against a pyramid of the depth drawn so far (the shapes, the characters and the
// first half). Each command is a run of the instance buffer's patches
// (cull::kInstances), so they are drawn in the same order as the one instanced draw.
void SceneRenderer::Impl::drawTerrainCulled(const View& view) {
  auto selection = terrain->select(glm::mat4(view.viewProjection), view.fovy, view.height);
  terrain->hidePatchesBehindPlanes(selection, view, -1);
  terrain::TerrainRenderer& renderer = terrain->renderer();
  const auto prepared = renderer.prepare(selection);
  stats->drawCalls += 1;
  stats->terrainTriangles = int(prepared.trianglesDrawn);
  const auto patches = std::uint32_t(renderer.patches().size());
  terrainCuller->clearClusters();
  terrainCuller->clearJobs();
  if (patches == 0) {
    terrainCuller->upload();  // this frame's counters: zero
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    terrain->keepMainSelection(std::move(selection));
    return;
  }
  const std::uint32_t first = terrainCuller->addClusters(terrainPatchBoxes(selection));
  const std::uint32_t split = patches / 2;
  cull::Job job;
  job.sphere = glm::vec4(0.0f, 0.0f, 0.0f, -1.0f);
  job.flags = cull::kInstances;
  job.firstCluster = first;
  job.clusterCount = split;
  const std::size_t near = terrainCuller->addJob(job);
  job.firstCluster = first + split;
  job.clusterCount = patches - split;
  job.firstInstance = split;
  const std::size_t far = terrainCuller->addJob(job);
  terrainCuller->upload();
  const auto uniforms = [this](const gl::Program& p) { draws->setUniforms(p); };
  const terrain::TerrainOutput output = terrain->beginSurface(view, drawFbo);
  for (const std::size_t j : {near, far}) {
    cullPhase(*terrainCuller, j, j + 1, view, j == far && render.msaa <= 1);
    const IndirectDraw commands = terrainCuller->commandsOf(j);
    renderer.drawIndirect(selection, gpu->eye(), uniforms, commands.offset, commands.count, output);
  }
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  terrain->shadeSurface(view, selection, drawFbo);
  terrain->keepMainSelection(std::move(selection));
}

}  // namespace engine
