#pragma once
// A glTF model's KHR_lights_punctual lights as scene lights (asset/scene_desc.h),
// placed by their nodes in the rest pose, so that a scene showing the model is lit
// the way the Khronos Sample Viewer lights it.
#include <vector>

#include <glm/glm.hpp>

#include "asset/model_data.h"
#include "asset/scene_desc.h"

namespace engine {

// Every light placed by a node of the default scene, in the order of the nodes:
// directional -> Sun (toward the light: the node's +Z; glTF lights shine along -Z),
// point -> Point and spot -> Spot at the node's origin with 1/d^2 falloff, a spot
// with its cones (its direction the node's +Z too). `root` places the model in the
// scene.
//
// Units: glTF gives directional intensity in lux and point/spot intensity in
// candela. The engine's sun of intensity I lights a surface facing it with
// irradiance I, and its point light with falloff with I / d^2, so 1 lux = 1 sun
// unit and 1 cd = 1 point unit: the values are taken as they are, which is also
// what the Sample Viewer does (intensity times the BRDF, no lm/W factor). Shadows
// are off, as in the Sample Viewer (a bulb inside its lamp's glass or shade would
// otherwise be shadowed by it). `range` is not used: the engine's lights reach
// everywhere (glTF allows an infinite range).
std::vector<LightDesc> modelLights(const ModelData& model, const glm::dmat4& root = glm::dmat4(1.0));

}  // namespace engine
