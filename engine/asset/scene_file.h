#pragma once
// Reads a scene file (JSON, see docs/scene-format.md) into a SceneDesc.
// Every error names the file, the JSON path and what was expected:
//   "demo.json: /models/2/speed: expected a number".
// Unknown keys are errors too, so a typo does not silently fall back to a default.
#include <map>
#include <string>

#include "asset/scene_desc.h"
#include "core/result.h"

namespace engine {

Result<SceneDesc> loadSceneFile(const std::string& path);
// Parses scene JSON text; `name` is used in messages and to resolve relative paths.
Result<SceneDesc> parseScene(const std::string& text, const std::string& name);
// render.ambient's names ("hemisphere", "sh", "ibl"), which demo --ambient takes too.
const std::map<std::string, Ambient>& ambientNames();
// The name of `ambient` in that map (for --describe).
std::string ambientName(Ambient ambient);
// render.shading's, render.tonemap's and render.output's names.
const std::map<std::string, Shading>& shadingNames();
const std::map<std::string, ToneMap>& toneMapNames();
const std::map<std::string, OutputCurve>& outputNames();
// render.skinning's and --skinning's names: vertex, compute, auto.
const std::map<std::string, Skinning>& skinningNames();
std::string skinningName(Skinning skinning);

}  // namespace engine
