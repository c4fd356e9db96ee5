#include "render/gpu_cull_pass.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <sstream>

#include "render/gpu_scene.h"
#include "render/pass_state.h"
#include "render/scene_draws.h"
#include "render/scene_stats.h"
#include "render/terrain_cull.h"
#include "render/terrain_pass.h"

namespace engine {

// The programs and the cluster table: every shape mesh's and every model
// primitive's clusters (made when they were uploaded), once per mesh.
Result<std::unique_ptr<GpuCullPass>> GpuCullPass::create(const std::string& shaderDir, const std::string& scenePath,
                                                         GLenum depthFormat, bool occlusion, float depthMargin,
                                                         const GpuScene& gpu, SceneDraws& draws, TerrainPass* terrain,
                                                         SceneStats* stats) {
  std::unique_ptr<GpuCullPass> pass(new GpuCullPass(gpu, draws, terrain, stats));
  pass->occlusion_ = occlusion;
  pass->depthMargin_ = depthMargin;
  const std::string context = scenePath + ": /render/gpu_culling: ";
  auto made = GpuCuller::create(shaderDir);
  if (!made) return makeError(context + made.error().message);
  pass->culler_ = std::make_unique<GpuCuller>(std::move(made).value());
  if (terrain) {
    auto forTerrain = GpuCuller::create(shaderDir);
    if (!forTerrain) return makeError(context + forTerrain.error().message);
    pass->terrainCuller_ = std::make_unique<GpuCuller>(std::move(forTerrain).value());
  }
  auto pyramid = HiZPyramid::create(shaderDir, depthFormat);
  if (!pyramid) return makeError(context + pyramid.error().message);
  pass->hiz_ = std::make_unique<HiZPyramid>(std::move(pyramid).value());
  GpuCuller& culler = *pass->culler_;
  for (const GpuMesh* mesh : gpu.meshes()) pass->shapeClusterBase_[mesh] = culler.addClusters(mesh->clusters());
  auto& primitiveClusterBase = pass->primitiveClusterBase_;
  for (const CharacterDraw& c : gpu.characters())
    for (const auto& mesh : c.instance->asset().gpu.meshes())
      for (const GpuPrimitive& p : mesh)
        if (!p.clusters.empty() && !primitiveClusterBase.count(&p)) primitiveClusterBase[&p] = culler.addClusters(p.clusters);
  return pass;
}

// A shape's job: its own matrix and clusters, its bounding sphere (none for a plane).
std::vector<IndirectDraw> GpuCullPass::queueShapeJob(const ShapeDraw& s) {
  cull::Job job;
  job.model = gpu_.shapeModel(s);
  job.sphere = s.radius < 0.0 ? glm::vec4(0.0f, 0.0f, 0.0f, -1.0f) : glm::vec4(glm::vec3(s.center - gpu_.eye()), float(s.radius));
  const cull::ClusterRange range = s.mesh->clusterRange();
  job.firstCluster = shapeClusterBase_.at(s.mesh) + range.first;
  job.clusterCount = range.count;
  return {culler_->commandsOf(culler_->addJob(job))};
}

// A character primitive's jobs, one per mesh instance, in the order drawPrimitive
// draws them: the clusters of the level of detail it will draw, the character's
// bounding sphere (of every pose: the bounds SceneDraws culls by). A
// skinned or morphed primitive's vertices move away from the rest positions its
// clusters were bounded by, so only its sphere is tested (cull::kInstanceOnly).
std::vector<IndirectDraw> GpuCullPass::queueCharacterJobs(const DrawItem& item) {
  const CharacterDraw& c = gpu_.characters()[size_t(item.object)];
  const ModelData& model = c.instance->asset().model;
  const NodeData& node = model.nodes[size_t(item.node)];
  const GpuPrimitive& prim = c.instance->asset().gpu.meshes()[size_t(node.mesh)][size_t(item.primitive)];
  const PrimitiveData& data = model.meshes[size_t(node.mesh)].primitives[size_t(item.primitive)];
  if (!hasClusters(prim, data.mode)) return {};
  const SkinMode mode = skinModeOf(c.desc);
  const int level = levelIndexWithin(prim, c.instance->lodBudget());
  const cull::ClusterRange range = level < 0 ? prim.fullClusters : prim.levels[size_t(level)].clusters;
  cull::Job job;
  const glm::dvec3 center = glm::dvec3(c.world * glm::dvec4(c.localCenter, 1.0)) - gpu_.eye();
  job.sphere = glm::vec4(glm::vec3(center), float(c.localRadius));
  job.firstCluster = primitiveClusterBase_.at(&prim) + range.first;
  job.clusterCount = range.count;
  job.flags = skinnedBy(node, data.influences, mode) || data.morphTargets > 0 ? cull::kInstanceOnly : 0u;
  std::vector<IndirectDraw> out;
  for (const glm::mat4& m : c.instance->instanceModels(mode, item.node, data.influences)) {
    job.model = m;
    out.push_back(culler_->commandsOf(culler_->addJob(job)));
  }
  return out;
}

ItemCommands GpuCullPass::queueJobs(const std::vector<DrawItem>& items) {
  ItemCommands out;
  out.reserve(items.size());
  for (const DrawItem& item : items) {
    out.push_back(item.source == DrawItem::Source::Shape ? queueShapeJob(gpu_.shapes()[size_t(item.object)])
                                                         : queueCharacterJobs(item));
  }
  return out;
}

// Culls jobs [firstJob, endJob) for the main view: against a pyramid of the depth
// drawn into the bound framebuffer so far, or the frustum alone. The depth only
// ever comes nearer during the view's pass (GL_GREATER, no clears), so what it
// hides now stays hidden for the rest of the pass.
void GpuCullPass::cullPhase(GpuCuller& with, std::size_t firstJob, std::size_t endJob, const View& view,
                                    bool occlusion) {
  if (endJob <= firstJob) return;
  // The pyramid needs the depth drawn so far, which llvmpipe rasterises only when
  // flushed: waited for here, so that the time below is the culling's own.
  if (occlusion) glFinish();
  const auto start = std::chrono::steady_clock::now();
  if (occlusion) {
    GLint framebuffer = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    hiz_->build(GLuint(framebuffer), view.width, view.height);
  }
  with.cull(firstJob, endJob, glm::mat4(view.viewProjection), occlusion ? hiz_.get() : nullptr, depthMargin_);
  ++stats_->cullDispatches;
  stats_->gpuCullMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Whether an opaque item can stand in the occluder prepass: a shape, or a model
// primitive that neither deforms (the prepass would need its skinning) nor cuts
// holes (MASK); either way one drawn in this very pass, so the depth it leaves in
// the prepass is depth the pass's own depth buffer will hold.
bool GpuCullPass::isOccluder(const DrawItem& item) const {
  if (item.source == DrawItem::Source::Shape) return true;
  const CharacterDraw& c = gpu_.characters()[size_t(item.object)];
  const ModelData& model = c.instance->asset().model;
  const NodeData& node = model.nodes[size_t(item.node)];
  const PrimitiveData& data = model.meshes[size_t(node.mesh)].primitives[size_t(item.primitive)];
  return !skinnedBy(node, data.influences, skinModeOf(c.desc)) && data.morphTargets == 0 &&
         c.instance->asset().gpu.material(data.material).alphaMode == AlphaMode::Opaque;
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
Status GpuCullPass::buildOccluderPyramid(const View& view, const std::vector<DrawItem>& occluders) {
  GLint framebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
  hiz_->copyDepth(GLuint(framebuffer), view.width, view.height);
  Status drawn = Ok{};
  if (!occluders.empty()) {
    glBindFramebuffer(GL_FRAMEBUFFER, hiz_->depthFramebuffer());
    const glm::mat4 viewProjection(view.viewProjection);
    drawn = draws_.draw(occluders, {true, viewProjection, viewProjection, false});
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(framebuffer));
  }
  hiz_->reduce();
  return drawn;
}

// Every list's jobs in the order the world draws them, culled in one dispatch
// against the occluder pyramid (above). A window's frames and a single offscreen
// frame cull alike: the pyramid is this frame's own, never the last frame's. MSAA,
// or no occluder: the frustum only.
Result<GpuCullPass::Commands> GpuCullPass::cull(const View& view, const DrawLists& lists) {
  culler_->clearJobs();
  Commands commands;
  commands.opaque = queueJobs(lists.opaque);
  commands.surface = queueJobs(lists.surface);
  commands.transmissive = queueJobs(lists.transmissive);
  commands.blend = queueJobs(lists.blend);
  culler_->upload();
  std::vector<DrawItem> occluders;
  std::copy_if(lists.opaque.begin(), lists.opaque.end(), std::back_inserter(occluders),
               [this](const DrawItem& item) { return isOccluder(item); });
  const bool occlusion = occlusion_ && !occluders.empty();
  // The occluders' depth waits for what is drawn before it: timed from there.
  if (occlusion) glFinish();
  const auto start = std::chrono::steady_clock::now();
  if (occlusion) {
    if (auto s = buildOccluderPyramid(view, occluders); !s) return s.error();
    applyPassState(opaquePassFor(view.mirrored));
  }
  culler_->cull(0, culler_->jobCount(), glm::mat4(view.viewProjection), occlusion ? hiz_.get() : nullptr, depthMargin_);
  ++stats_->cullDispatches;
  stats_->gpuCullMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return commands;
}

// The boxes of the terrain's drawn patches (terrainPatchBox): the terrain
// culler's clusters, one a patch.
std::vector<cull::Cluster> GpuCullPass::terrainPatchBoxes(const terrain::LodSelection& selection) const {
  std::vector<cull::Cluster> out;
  const auto count = std::uint32_t(terrain::TerrainRenderer::indexCount());
  for (const terrain::LodPatch& p : terrain_->renderer().patches())
    out.push_back(terrainPatchBox(terrain_->terrain(), selection, p, count));
  return out;
}

// The terrain's selection (CPU-culled to the frustum by the CDLOD traversal, as
// without) in two halves of the drawing order, the first culled against the
// frustum alone, the second against a pyramid of the depth drawn so far (the
// shapes, the characters and the first half). Each command is a run of the instance buffer's patches
// (cull::kInstances), so they are drawn in the same order as the one instanced draw.
void GpuCullPass::drawTerrain(const View& view, const gl::Framebuffer& target) {
  auto selection = terrain_->select(glm::mat4(view.viewProjection), view.fovy, view.height);
  terrain_->hidePatchesBehindPlanes(selection, view, -1);
  terrain::TerrainRenderer& renderer = terrain_->renderer();
  const auto prepared = renderer.prepare(selection);
  stats_->drawCalls += 1;
  stats_->terrainTriangles = int(prepared.trianglesDrawn);
  const auto patches = std::uint32_t(renderer.patches().size());
  terrainCuller_->clearClusters();
  terrainCuller_->clearJobs();
  if (patches == 0) {
    terrainCuller_->upload();  // this frame's counters: zero
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    terrain_->keepMainSelection(std::move(selection));
    culler_->bindCommands();
    return;
  }
  const std::uint32_t first = terrainCuller_->addClusters(terrainPatchBoxes(selection));
  const std::uint32_t split = patches / 2;
  cull::Job job;
  job.sphere = glm::vec4(0.0f, 0.0f, 0.0f, -1.0f);
  job.flags = cull::kInstances;
  job.firstCluster = first;
  job.clusterCount = split;
  const std::size_t near = terrainCuller_->addJob(job);
  job.firstCluster = first + split;
  job.clusterCount = patches - split;
  job.firstInstance = split;
  const std::size_t far = terrainCuller_->addJob(job);
  terrainCuller_->upload();
  const auto uniforms = [this](const gl::Program& p) { draws_.setUniforms(p); };
  const terrain::TerrainOutput output = terrain_->beginSurface(view, target);
  for (const std::size_t j : {near, far}) {
    cullPhase(*terrainCuller_, j, j + 1, view, j == far && occlusion_);
    const IndirectDraw commands = terrainCuller_->commandsOf(j);
    renderer.drawIndirect(selection, gpu_.eye(), uniforms, commands.offset, commands.count, output);
  }
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  terrain_->shadeSurface(view, selection, target);
  terrain_->keepMainSelection(std::move(selection));
  culler_->bindCommands();
}

CullStats GpuCullPass::counters() const {
  CullStats out;
  const cull::Counters c = culler_->counters();
  out.enabled = true;
  out.instancesTested = c.instancesTested;
  out.instancesFrustum = c.instancesFrustum;
  out.instancesOccluded = c.instancesOccluded;
  out.clustersTested = c.clustersTested;
  out.clustersFrustum = c.clustersFrustum;
  out.clustersOccluded = c.clustersOccluded;
  if (terrainCuller_) {
    const cull::Counters t = terrainCuller_->counters();
    out.patchesTested = t.clustersTested;
    out.patchesFrustum = t.clustersFrustum;
    out.patchesOccluded = t.clustersOccluded;
  }
  return out;
}

// "gpu-culling(1234 clusters of <= 128 triangles; frustum + hi-z, occluder prepass)".
std::string GpuCullPass::describe() const {
  std::ostringstream out;
  out << "gpu-culling(" << culler_->clusters().size() << " clusters of <= " << cull::kClusterTriangles
      << " triangles; " << (occlusion_ ? "frustum + hi-z, occluder prepass" : "frustum only (msaa)")
      << (terrainCuller_ ? "; terrain patches too" : "") << ")";
  return out.str();
}

}  // namespace engine
