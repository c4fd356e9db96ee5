#pragma once
// GPU culling of the main view (render.gpu_culling, render/gpu_cull.h): its draw
// items' instances and clusters culled in one dispatch against a pyramid of the
// depth its occluders leave, and the terrain's patches in two halves, the second
// against the depth drawn before it; the draws then submit the indirect commands
// it writes. Not part of the engine's interface.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/result.h"
#include "gl/resources.h"
#include "render/gpu_cull.h"
#include "render/mesh.h"
#include "render/model_renderer.h"
#include "render/scene_view.h"
#include "terrain/lod.h"

namespace engine {

class GpuScene;
class SceneDraws;
class TerrainPass;
struct CullStats;
struct SceneStats;
struct ShapeDraw;

class GpuCullPass {
 public:
  // `depthFormat`: the frame target's depth, which the pyramid copies;
  // `occlusion`: the frame is single-sample (MSAA's pyramid would need every
  // sample's depth: the frustum only); `depthMargin`: cull::View's. Errors name
  // `scenePath`.
  static Result<std::unique_ptr<GpuCullPass>> create(const std::string& shaderDir, const std::string& scenePath,
                                                     GLenum depthFormat, bool occlusion, float depthMargin,
                                                     const GpuScene& gpu, SceneDraws& draws, TerrainPass* terrain,
                                                     SceneStats* stats);

  // The commands of a view's draw lists, aligned with each.
  struct Commands {
    ItemCommands opaque, surface, transmissive, blend;
  };
  // The main view's lists culled before any of them is drawn into the bound
  // framebuffer (cleared): the commands are ready for the draws.
  Result<Commands> cull(const View& view, const DrawLists& lists);
  // The main view's terrain, after its opaque draws, into the bound framebuffer;
  // `target`: the frame's (it holds the deferred terrain's surface). Leaves the
  // view's commands bound again.
  void drawTerrain(const View& view, const gl::Framebuffer& target);
  // The last frame's counters, read back (waits).
  CullStats counters() const;
  std::string describe() const;

 private:
  GpuCullPass(const GpuScene& gpu, SceneDraws& draws, TerrainPass* terrain, SceneStats* stats)
      : gpu_(gpu), draws_(draws), terrain_(terrain), stats_(stats) {}
  ItemCommands queueJobs(const std::vector<DrawItem>& items);
  std::vector<IndirectDraw> queueShapeJob(const ShapeDraw& shape);
  std::vector<IndirectDraw> queueCharacterJobs(const DrawItem& item);
  bool isOccluder(const DrawItem& item) const;
  Status buildOccluderPyramid(const View& view, const std::vector<DrawItem>& occluders);
  void cullPhase(GpuCuller& with, std::size_t firstJob, std::size_t endJob, const View& view, bool occlusion);
  std::vector<cull::Cluster> terrainPatchBoxes(const terrain::LodSelection& selection) const;

  const GpuScene& gpu_;
  SceneDraws& draws_;
  TerrainPass* terrain_;
  SceneStats* stats_;
  bool occlusion_ = true;
  float depthMargin_ = cull::kDepthMargin;
  // Made at load with every mesh's clusters; where each mesh's clusters start in
  // its table.
  std::unique_ptr<GpuCuller> culler_;
  std::unique_ptr<GpuCuller> terrainCuller_;  // the terrain's patches, a table of their own each frame
  std::unique_ptr<HiZPyramid> hiz_;
  std::map<const GpuMesh*, std::uint32_t> shapeClusterBase_;
  std::map<const GpuPrimitive*, std::uint32_t> primitiveClusterBase_;
};

}  // namespace engine
