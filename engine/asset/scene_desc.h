#pragma once
// A scene as its file describes it (assets/scenes/*.json): camera, lights, sky,
// fog, terrain, glTF models, analytic primitives with materials, render settings.
// Plain data: the rasterizer and the ray tracer each build what they need from it,
// and only what the scene contains.
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "asset/material_layers.h"

namespace engine {

struct CameraDesc {
  glm::dvec3 position{0.0, 1.5, 5.0};
  glm::dvec3 forward{0.0, 0.0, -1.0};  // normalised
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fovyDegrees = 60.0;
  double nearPlane = 0.05;
  double farPlane = 1000.0;
  // The course's room is left-handed (camera looks along +z, +x on the right);
  // glTF and GL are right-handed. The screen's right is cross(up, forward) for a
  // left-handed scene and cross(forward, up) for a right-handed one.
  bool leftHanded = false;
  glm::dvec3 right() const;
};

enum class LightType { Sun, Point, Area, Spot };

struct LightDesc {
  LightType type = LightType::Sun;
  // Sun: toward the light, normalised. Spot: the cone's axis turned toward the light
  // (the way it shines, reversed), normalised, so that for both it is the direction
  // toward the light from what it lights.
  glm::dvec3 direction{0.0, 1.0, 0.0};
  glm::dvec3 position{0.0};  // Point, Spot and Area (the centre)
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  bool falloff = false;     // Point and Spot: 1/d^2 when true, none when false (the course)
  bool shadows = true;
  // Sun: the disk's angular diameter in degrees. 0 is a delta direction (sharp shadows);
  // the path tracer samples a wider sun as a cone of that size (soft shadows), which the
  // rasterizer's shadow map and the Whitted tracer do not.
  float angleDegrees = 0.0f;
  glm::dvec3 edgeU{1.0, 0.0, 0.0};  // Area: the two edge vectors, full length
  glm::dvec3 edgeV{0.0, 0.0, 1.0};
  // Spot: the half-angles of the cone of full light and of the cone beyond which
  // there is none, in degrees (0 <= inner <= outer <= 90; glTF's defaults). Between
  // them the light fades (shaders/common/spot_cone.glsl).
  float innerConeDegrees = 0.0f;
  float outerConeDegrees = 45.0f;
};

// The classic model of the course, and glTF's metallic-roughness.
struct MaterialDesc {
  std::string name;
  glm::vec3 color{0.8f};
  float ambient = 0.1f;     // classic: colour * ambient, unshadowed
  float diffuse = 0.9f;     // classic: colour * diffuse * N.L * visibility
  float specular = 0.0f;    // classic Blinn-Phong highlight weight
  float shininess = 32.0f;
  float reflection = 0.0f;  // mirror weight of the reflected ray
  float metallic = 0.0f;
  float roughness = 0.6f;
  // Radiance the surface emits, in the units of a light's colour * intensity. Both
  // renderers add it; to the path tracer the surface is a light its paths can reach.
  glm::vec3 emission{0.0f};
  // Metallic-roughness only: glTF's ior, specular and clear coat (set from glTF
  // materials; scene files do not have them yet).
  MaterialLayers layers;
  std::string texture;      // "" | "checker" | an image path (relative to the scene)
  float textureScale = 1.0f;
};

enum class PrimitiveType { Sphere, Plane, Box };

struct PrimitiveDesc {
  PrimitiveType type = PrimitiveType::Sphere;
  glm::dvec3 center{0.0};   // Sphere
  double radius = 1.0;      // Sphere
  glm::dvec3 point{0.0};    // Plane: a point on it
  glm::dvec3 normal{0.0, 1.0, 0.0};  // Plane, normalised
  double extent = 0.0;      // Plane: half size for the rasterizer (0 = scene's far)
  glm::dvec3 min{0.0}, max{1.0};     // Box
  int material = 0;         // index into SceneDesc::materials
};

struct ModelDesc {
  std::string path;  // resolved against the scene file's folder
  glm::dvec3 position{0.0};
  glm::dvec3 rotationDegrees{0.0};  // applied as Z * Y * X... see scene_file.cpp
  glm::dvec3 scale{1.0};
  std::string clip;     // "" = the first clip; a name or an index
  double speed = 1.0;
  double start = 0.0;   // clip time at scene time 0
  bool dualQuat = false;
  // Drawn in the bind pose without skinning: the baseline skinning is measured
  // against (bench/skinning_cost).
  bool unskinned = false;
  bool onTerrain = false;  // position.y is a height above the terrain there
};

struct SkyDesc {
  bool enabled = true;  // false: the background colour
  glm::vec3 zenith{0.15f, 0.35f, 1.0f};
  glm::vec3 horizon{0.6f, 0.7f, 0.85f};
  glm::vec3 ground{0.3f, 0.28f, 0.25f};
  glm::vec3 background{0.0f};
  bool sunDisk = true;  // the gradient's; an image's sun is in its pixels
  // A lat-long image (Radiance .hdr or PNG, resolved against the scene file's folder)
  // in place of the gradient: its radiance times `intensity`, turned about +y by
  // `rotationDegrees` (counter-clockwise seen from above: the image's centre, at +z
  // unturned, goes toward +x). Both renderers sample it (raytrace/environment.h).
  std::string image;
  float intensity = 1.0f;
  float rotationDegrees = 0.0f;
};

enum class FogModel { Exponential, Volumetric };

// Exponential: the colour blended in by exp(-density * distance) at the first hit, in
// every renderer. Volumetric: a homogeneous medium filling the scene, scattering and
// absorbing per metre (RGB) with Henyey-Greenstein's anisotropy, which the CPU path
// tracer renders as the truth (raytrace/medium.h); the rasterizer and the Whitted
// tracer draw its exponential stand-in, `density` the mean extinction.
// A volumetric fog with a height falloff is an exponential height fog: its
// coefficients are those at y = 0, times exp(-heightFalloff * y) elsewhere.
struct FogDesc {
  bool enabled = false;
  float density = 0.02f;
  glm::vec3 color{0.6f, 0.7f, 0.85f};
  FogModel model = FogModel::Exponential;
  glm::vec3 scattering{0.0f}, absorption{0.0f};
  float anisotropy = 0.0f;
  float heightFalloff = 0.0f;  // per metre; 0: homogeneous
};

// A planet's atmosphere under the scene (Hillaire 2020's model, Earth's coefficients
// by default, per metre): the planet's surface passes through y = 0 with its centre
// straight below the origin, and its air thins with the altitude, Rayleigh's and
// Mie's exponentially, ozone's as a tent. Present, it is the sky in every renderer:
// the path tracer renders it as a medium, the rasterizer from its tables.
struct AtmosphereDesc {
  bool enabled = false;
  double planetRadius = 6360e3;
  double thickness = 100e3;  // to the top of the air
  glm::vec3 rayleighScattering{5.802e-6f, 13.558e-6f, 33.1e-6f};
  float rayleighScaleHeight = 8000.0f;
  glm::vec3 mieScattering{3.996e-6f};
  glm::vec3 mieAbsorption{0.444e-6f};
  float mieScaleHeight = 1200.0f;
  float mieAnisotropy = 0.8f;  // Henyey-Greenstein's g
  glm::vec3 ozoneAbsorption{0.650e-6f, 1.881e-6f, 0.085e-6f};
  float ozoneCenter = 25000.0f;  // the tent's peak, metres above the ground
  float ozoneHalfWidth = 15000.0f;
  glm::vec3 groundAlbedo{0.3f};
};

// A bounded medium: an axis-aligned box of homogeneous fog (a room's haze, a patch of
// mist), coefficients per metre as a volumetric fog's.
struct MediumDesc {
  glm::dvec3 min{0.0}, max{0.0};
  glm::vec3 scattering{0.0f}, absorption{0.0f};
  float anisotropy = 0.0f;
};

enum class Shading { Classic, Pbr };
enum class ShadowFilter { Hard, Pcf };
enum class ToneMap { None, Reinhard, Aces };
enum class OutputCurve { Srgb, Gamma22 };
// The rasterizer's PBR ambient (classic shading keeps its own): HEMISPHERE mixes two
// colours of the sky by the normal; SH takes the diffuse from the environment's
// order-2 SH irradiance and the specular from the same irradiance in the mirror
// direction (a lobe as blurry as the diffuse); IBL the split-sum's prefiltered
// environment for the specular. The path tracer needs none of them.
enum class Ambient { Hemisphere, Sh, Ibl };

// How the rasterizer deforms skinned and morphed models: in each pass's vertex
// shader, or once per pose by a compute shader into a skin cache that every pass
// draws as a static mesh (render/skin_cache.h).
// Where characters deform: in every pass's vertex shader, once a frame into the
// skin cache, or (auto) the cache where it pays (scene_renderer.cpp's usesSkinCache).
enum class Skinning { Vertex, Compute, Auto };

struct RenderDesc {
  int msaa = 1;
  int supersample = 1;  // render N x N times larger, average down
  Shading shading = Shading::Pbr;
  int shadowMapSize = 2048;
  ShadowFilter shadowFilter = ShadowFilter::Pcf;
  int pcfKernel = 3;
  float exposure = 1.0f;
  ToneMap toneMap = ToneMap::Aces;
  OutputCurve output = OutputCurve::Srgb;
  // Cube map size of the rasterizer's reflection probes (one per mirror sphere or
  // box); 0: mirrors show only their own shading.
  int reflectionProbe = 256;
  // PBR ambient; unset: IBL under a sky, the hemisphere without one (render.ambient).
  std::optional<Ambient> ambient;
  int iblSize = 128;  // texels a side of the environment's cube map (render.ibl_size)
  Skinning skinning = Skinning::Auto;  // render.skinning: "vertex", "compute" or "auto"
  // render.lod_pixels: models' levels of detail (asset/mesh_lod.h) are drawn where
  // their error is within this many pixels on screen; 0, the default, draws every
  // mesh in full.
  double lodPixels = 0.0;
  // render.gpu_culling: the main view's meshes culled per instance and per cluster
  // of 128 triangles in a compute shader, against the frustum and the depth drawn
  // so far (render/gpu_cull.h). Changes no pixel; off by default (docs/rasterizer.md,
  // "GPU culling"; what it costs and saves on llvmpipe: docs/bench-log/gpu-culling.md).
  bool gpuCulling = false;
};

struct TerrainDesc {
  bool enabled = false;
  std::string heightmap;  // image path, or "" for procedural
  unsigned seed = 1;
  double size = 256.0;
  double heightScale = 20.0;
  double spacing = 1.0;       // metres between samples (procedural)
  double errorPixels = 2.0;   // level-of-detail target: screen-space error
  glm::dvec3 origin{0.0};
};

struct SceneDesc {
  std::string path;
  CameraDesc camera;
  std::vector<LightDesc> lights;
  std::vector<MaterialDesc> materials;
  std::vector<PrimitiveDesc> primitives;
  std::vector<ModelDesc> models;
  SkyDesc sky;
  FogDesc fog;
  AtmosphereDesc atmosphere;
  std::vector<MediumDesc> media;
  TerrainDesc terrain;
  RenderDesc render;
  float ambient = 0.1f;  // classic shading's ambient term when a material has none
};

// A model's placement, with `groundHeight` added to its y (terrain under it):
// translation, then yaw (y), pitch (x), roll (z), then scale. Both renderers use it.
inline glm::dmat4 modelTransform(const ModelDesc& desc, double groundHeight = 0.0) {
  glm::dmat4 world = glm::translate(glm::dmat4(1.0), desc.position + glm::dvec3(0.0, groundHeight, 0.0));
  world = glm::rotate(world, glm::radians(desc.rotationDegrees.y), glm::dvec3(0, 1, 0));
  world = glm::rotate(world, glm::radians(desc.rotationDegrees.x), glm::dvec3(1, 0, 0));
  world = glm::rotate(world, glm::radians(desc.rotationDegrees.z), glm::dvec3(0, 0, 1));
  return glm::scale(world, desc.scale);
}

// The ambient light both renderers use for PBR shading: a hemisphere from the
// sky's colours (dimmed), or the scene's ambient grey without a sky.
inline glm::vec3 ambientSkyColor(const SceneDesc& scene) {
  return scene.sky.enabled ? scene.sky.zenith * 0.35f + scene.sky.horizon * 0.15f : glm::vec3(scene.ambient);
}
// The PBR ambient the rasterizer draws `scene` with: the scene's choice, else IBL
// where there is a sky to light with (a planet's air is one).
inline Ambient ambientOf(const SceneDesc& scene) {
  return scene.render.ambient.value_or(scene.sky.enabled || scene.atmosphere.enabled ? Ambient::Ibl
                                                                                      : Ambient::Hemisphere);
}
inline glm::vec3 ambientGroundColor(const SceneDesc& scene) {
  return scene.sky.enabled ? scene.sky.ground * 0.3f : glm::vec3(scene.ambient);
}

}  // namespace engine
