#pragma once
// `demo --mode raytrace|pathtrace --device gpu --offscreen`: the scene built as the
// CPU tracer builds it, traced by the GPU Whitted integrator or path tracer
// (engine/gputrace) on an offscreen context, tone mapped by the CPU's own code.
#include <string>

#include "app/runner.h"
#include "asset/scene_desc.h"
#include "core/result.h"
#include "raytrace/scene_builder.h"

namespace demo {

// Errors: "--device gpu: double precision is not supported" and the like for what the
// GPU path cannot draw, or a context or shader failure.
engine::Result<engine::rt::RaytraceRun> gpuRaytraceScene(const engine::SceneDesc& scene, double time,
                                                         const engine::rt::RenderSettings& settings,
                                                         engine::Backend backend, const std::string& shaderDir);

}  // namespace demo
