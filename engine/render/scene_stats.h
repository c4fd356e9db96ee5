#pragma once
// What a frame of the scene renderer counted and timed (SceneRenderer::stats,
// cullStats, passTimes; demo --bench and the trade panel print them), apart from the
// renderer so that its passes fill them without including it.
#include <string>

namespace engine {

struct SceneStats {
  int drawCalls = 0;
  int programChanges = 0;
  // The least program changes the frame's draws allow: the distinct programs of
  // each pass, summed. Sorted draws (render/draw_items.h) bind each once.
  int programsNeeded = 0;
  int objectsCulled = 0;
  int objectsDrawn = 0;
  int terrainTriangles = 0;
  // The terrain's patches left out because an opaque plane hides them
  // (render/plane_occlusion.h), over the frame's views.
  int terrainPatchesHidden = 0;
  // Terrain blocks whose errors are still to be measured for this view (a few a
  // frame): until none are, the terrain's level of detail may still coarsen.
  int terrainBlocksPending = 0;
  // The image height the main view's terrain was selected for (the target's, which
  // supersampling enlarges): a tracer's reference of that view selects with it.
  int terrainViewportHeight = 0;
  long long verticesDeformed = 0;  // by the skin cache's compute (render.skinning compute)
  // Full-frame copies into the caller's framebuffer: the post pass, or the direct
  // path's copy when the caller's framebuffer could not be drawn into (0 or 1).
  int frameCopies = 0;
  // 1 when the sun's maps kept their shapes and terrain from an earlier frame (the
  // camera stood still: see SunShadowPass::MapsKey), 0 when drawn anew.
  int sunStaticKept = 0;
  // CPU time: the last update's posing (the scene layer's sampling and the copy of
  // its poses), this frame's collecting and sorting of draw items (culling
  // included), and its submission of them.
  double animationMs = 0.0;
  double cullMs = 0.0;
  double submitMs = 0.0;
  // GPU culling (render.gpu_culling): the CPU time of its passes, the pyramids'
  // builds and the dispatches, after a glFinish that waits for the depth they read
  // (the frame would wait for it at its end anyway); and its dispatches.
  double gpuCullMs = 0.0;
  int cullDispatches = 0;
};

// GPU culling's counters of the last frame (render/cull_math.h's Counters):
// instances and clusters tested, culled by the frustum, culled by occlusion.
struct CullStats {
  bool enabled = false;
  long long instancesTested = 0, instancesFrustum = 0, instancesOccluded = 0;
  long long clustersTested = 0, clustersFrustum = 0, clustersOccluded = 0;
  // The terrain's CDLOD patches (the main view's selection).
  long long patchesTested = 0, patchesFrustum = 0, patchesOccluded = 0;
};

// One pass's GPU time (a GL_TIME_ELAPSED query), from the latest frame whose
// result the GL has: reading never waits, so a figure may be a frame or two old.
struct PassTime {
  std::string pass;  // as --describe names it: skinning, shadow-sun, shadow-point, reflection-probes, world, post
  double gpuMs = 0.0;
};

}  // namespace engine
