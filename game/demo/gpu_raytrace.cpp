#include "gpu_raytrace.h"

#include "gputrace/gpu_tracer.h"
#include "platform/gl_context.h"
#include "raytrace/tone_map.h"

namespace demo {

engine::Result<engine::rt::RaytraceRun> gpuRaytraceScene(const engine::SceneDesc& desc, double time,
                                                         const engine::rt::RenderSettings& settings,
                                                         engine::Backend backend, const std::string& shaderDir) {
  engine::rt::RaytraceRun run;
  auto scene = engine::rt::buildRtScene(desc, time, settings.height, &run.build);
  if (!scene) return scene.error();
  if (const std::string why = engine::gpurt::unsupported(*scene, settings); !why.empty()) {
    return engine::makeError("--device gpu: " + why);
  }
  engine::ContextOptions context;
  context.width = 16;  // the image is a storage buffer, not the context's surface
  context.height = 16;
  auto gl = engine::createContext(backend, context);
  if (!gl) return engine::makeError("--device gpu: " + gl.error().message);
  auto tracer = engine::gpurt::GpuTracer::create(*scene, shaderDir);
  if (!tracer) return tracer.error();
  auto result = tracer->render(settings);
  if (!result) return result.error();
  run.result = std::move(result).value();
  run.image = engine::rt::toImage(run.result.image, scene->render());
  return run;
}

}  // namespace demo
