#pragma once
// Everything a colour view shows, into the bound framebuffer (cleared): the view's
// opaque draws, the terrain, the sky where neither is, the transmissive draws over
// a copy of those, then the blended ones. The main view's deferred characters come
// first, and with GPU culling its draws are culled first. Probes draw their faces
// through it too. Not part of the engine's interface.
#include "core/result.h"
#include "render/scene_view.h"

namespace engine {

class CharacterSurfacePass;
class GpuCullPass;
class OutputPass;
class SceneDraws;
class SkyPass;
class TerrainPass;
class TransmissionPass;

class WorldPass {
 public:
  // The passes it sequences; null where the scene has none.
  WorldPass(SceneDraws& draws, SkyPass& sky, const OutputPass& output, TerrainPass* terrain,
            CharacterSurfacePass* surfaces, TransmissionPass* transmission, GpuCullPass* culling)
      : draws_(draws),
        sky_(sky),
        output_(output),
        terrain_(terrain),
        surfaces_(surfaces),
        transmission_(transmission),
        culling_(culling) {}

  // `skipShape`: a probe's own mirror, not drawn; `useProbes`: mirrors show their
  // probe (not in the probes' own views).
  Status draw(const View& view, int skipShape, bool useProbes);

 private:
  Status drawCulled(const View& view, const DrawLists& lists, bool useProbes);

  SceneDraws& draws_;
  SkyPass& sky_;
  const OutputPass& output_;
  TerrainPass* terrain_;
  CharacterSurfacePass* surfaces_;
  TransmissionPass* transmission_;
  GpuCullPass* culling_;
};

}  // namespace engine
