#include "raytrace/describe.h"

#include <algorithm>
#include <cstdio>

#include "raytrace/whitted_packets.h"
#include "raytrace/whitted_tracer.h"

namespace engine::rt {
namespace {

// Each BVH group by name with its triangles; a run of groups alike (a crowd of one
// model) as one entry with its count.
std::string groupsOf(const RtScene& scene) {
  std::string out = "BVH groups:";
  for (int g = 0; g < scene.groupCount();) {
    const std::size_t triangles = scene.groupTriangleMeshes(g).size();
    int same = 1;
    while (g + same < scene.groupCount() && scene.groupName(g + same) == scene.groupName(g) &&
           scene.groupTriangleMeshes(g + same).size() == triangles) {
      ++same;
    }
    out += (g == 0 ? " " : ", ") + (scene.groupName(g).empty() ? "group " + std::to_string(g) : scene.groupName(g));
    out += same > 1 ? " x" + std::to_string(same) + " (" + std::to_string(triangles) + " triangles each)"
                    : " (" + std::to_string(triangles) + " triangles)";
    g += same;
  }
  return out;
}

std::string lightsOf(const RtScene& scene) {
  int sun = 0, point = 0, spot = 0, area = 0, shadowed = 0;
  for (const LightDesc& l : scene.lights()) {
    sun += l.type == LightType::Sun ? 1 : 0;
    point += l.type == LightType::Point ? 1 : 0;
    spot += l.type == LightType::Spot ? 1 : 0;
    area += l.type == LightType::Area ? 1 : 0;
    shadowed += l.shadows ? 1 : 0;
  }
  char text[160];
  std::snprintf(text, sizeof(text), "lights: %d sun, %d point, %s%d area (%d casting shadows)", sun, point,
                spot > 0 ? (std::to_string(spot) + " spot, ").c_str() : "", area, shadowed);
  return text;
}

// The fog as this integrator draws it: a volumetric fog is a medium to the path
// tracer, its exponential stand-in to the Whitted tracer.
std::string fogOf(const FogDesc& fog, const RenderSettings& settings) {
  if (!fog.enabled) return "";
  if (fog.model == FogModel::Exponential || settings.method != Method::Path) return ", fog (exponential)";
  char text[200];
  const glm::vec3 e = fog.scattering + fog.absorption;
  std::snprintf(text, sizeof(text), ", fog: a %s medium (extinction %g %g %g /m%s, albedo %g %g %g, g %g)",
                fog.heightFalloff > 0.0f ? "height" : "homogeneous", e.x, e.y, e.z,
                fog.heightFalloff > 0.0f ? " at y = 0" : "", e.x > 0.0f ? fog.scattering.x / e.x : 0.0f,
                e.y > 0.0f ? fog.scattering.y / e.y : 0.0f, e.z > 0.0f ? fog.scattering.z / e.z : 0.0f, fog.anisotropy);
  std::string out = text;
  if (fog.heightFalloff > 0.0f) {
    std::snprintf(text, sizeof(text), ", thinning e-fold every %g m", 1.0 / double(fog.heightFalloff));
    out.insert(out.size() - 1, text);
  }
  return out;
}

// The atmosphere and the boxes of fog: media to the path tracer, not drawn by the
// Whitted tracer.
std::string mediaOf(const RtScene& scene, const RenderSettings& settings) {
  const AtmosphereDesc& air = scene.atmosphere();
  const std::size_t boxes = scene.media().size();
  if (!air.enabled && boxes == 0) return "";
  if (settings.method != Method::Path) return ", atmosphere and boxes of fog not drawn";
  std::string out;
  char text[200];
  if (air.enabled) {
    std::snprintf(text, sizeof(text), ", atmosphere: a planet of radius %g km under %g km of air (Rayleigh, Mie, ozone)",
                  air.planetRadius / 1e3, air.thickness / 1e3);
    out += text;
  }
  if (boxes > 0) out += ", " + std::to_string(boxes) + (boxes == 1 ? " box" : " boxes") + " of fog";
  if (settings.mediumScatterings >= 0) out += ", " + std::to_string(settings.mediumScatterings) + " scattering(s) at most";
  return out;
}

std::string environmentOf(const Environment& environment) {
  if (const FloatImage* image = environment.image()) {
    return "environment: image " + std::to_string(image->width) + "x" + std::to_string(image->height);
  }
  return environment.isConstant() ? "environment: background colour" : "environment: gradient sky";
}

// How many rays meet the spheres and planes at once: the Whitted tracer's packets
// (whitted_packets.h) or its samples one at a time and why, and then whether a row's
// camera rays find their first hits together (whitted_tracer.cpp's SpanTracer); the path
// tracer's bounces eight or four to a pass (RtScene::intersectMany).
std::string lanesOf(const RtScene& scene, const RenderSettings& s) {
  if (s.method == Method::Path) {
    if (s.precision == Precision::Double) return "shapes: one ray at a time (double precision)";
    return scene.eightRaysAtATime() ? "shapes: eight rays at a time (AVX2)" : "shapes: four rays at a time (SSE)";
  }
  if (const char* why = WhittedPackets::unsupported(scene, s)) {
    return std::string("packets: none, one sample at a time (") + why + ")" +
           (WhittedIntegrator::firstHitsInRows(s) ? "; first hits eight camera rays at a time (AVX2)" : "");
  }
  return "packets: eight camera samples at a time, shadow rays too (AVX2)";
}

}  // namespace

std::string describe(const RtScene& scene, const RenderSettings& s) {
  const bool path = s.method == Method::Path;
  std::string out;
  char line[256];
  std::snprintf(line, sizeof(line), "tracer: %s, %s, %dx%d, spp %d, max depth %d", path ? "path" : "whitted",
                s.precision == Precision::Double ? "double" : "float", s.width, s.height, s.samplesPerPixel, s.maxDepth);
  out += line;
  out += path ? ", roulette from depth " + std::to_string(s.rouletteDepth) + "\n"
              : ", " + std::to_string(s.shadowSamples) + "x" + std::to_string(s.shadowSamples) + " area shadow rays\n";
  out += lanesOf(scene, s) + "\n";
  std::size_t meshTriangles = 0, textured = 0, layered = 0;
  for (const RtMesh& m : scene.meshes()) meshTriangles += m.indices.size() / 3;
  for (int m = 0; m < int(scene.materials().size()); ++m) {
    textured += scene.extras(m).readsUv() ? 1 : 0;
    layered += scene.materials()[std::size_t(m)].layers.isDefault() ? 0 : 1;
  }
  std::snprintf(line, sizeof(line), "shapes: %zu spheres, %zu planes, %zu meshes (%zu triangles) in %d BVH groups\n",
                scene.sphereCount(), scene.planeCount(), scene.meshes().size(), meshTriangles, scene.groupCount());
  out += line;
  out += groupsOf(scene) + "\n";
  out += lightsOf(scene) + "\n";
  std::snprintf(line, sizeof(line), "materials: %zu (%zu textured, %zu with glTF layers), %zu textures, %s shading\n",
                scene.materials().size(), textured, layered, scene.textures().size(),
                scene.render().shading == Shading::Pbr ? "pbr" : "classic");
  out += line;
  out += environmentOf(scene.environment()) + fogOf(scene.fog(), s) + mediaOf(scene, s) + "\n";
  return out;
}

}  // namespace engine::rt
