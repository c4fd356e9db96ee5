#pragma once
// The pose of a model at one time as JSON, in the format of the conformance
// reference poses (../shared/conformance/README.md), so that the viewer's
// --dump-pose output can be compared with three.js directly:
//   {"time", "anim", "nodes": [{"node", "world": [16, column-major]}],
//    "meshes": [{"node", "mesh", "primitive", "morphTargets", "morphWeights": [...],
//                "count", "positions": [x, y, z, ...]}]}
// Positions are world space after morphing, then linear-blend skinning; a
// skinned primitive ignores its node's own transform, as glTF requires.
// morphWeights are the instance's weights at `time` (empty without targets).
#include <nlohmann/json.hpp>

#include "anim/player.h"
#include "asset/model_data.h"
#include "core/result.h"

namespace engine {

// `animation` = -1 gives the rest pose. `time` is wrapped as
// poses/CONVENTIONS.md says: Repeat maps t to t - D * floor(t / D) (t = D gives
// the pose at 0), Clamp to clamp(t, 0, D), D being the clip's largest last key.
Result<nlohmann::json> dumpPose(const ModelData& model, int animation, double time,
                                LoopMode loop = LoopMode::Repeat);

}  // namespace engine
