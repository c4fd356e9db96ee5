#include "asset/scene_file.h"
#include "asset/scene_file_node.h"

#include "core/linear_image.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

namespace engine {
namespace {
using namespace scenefile;

Status readCamera(const Node& n, CameraDesc& c) {
  TRY(n.expectObject({"position", "target", "direction", "up", "fovy", "near", "far", "handedness"}));
  TRY(readVec3(n, "position", c.position));
  if (n.has("target") && n.has("direction")) return n.error("give either target or direction, not both");
  if (n.has("target")) {
    glm::dvec3 target(0.0);
    TRY(readVec3(n, "target", target));
    if (target == c.position) return n.at("target").error("the target is the camera position");
    c.forward = glm::normalize(target - c.position);
  }
  TRY(readDirection(n, "direction", c.forward));
  TRY(readDirection(n, "up", c.up));
  if (glm::length(glm::cross(c.forward, c.up)) < 1e-9) return n.error("up is parallel to the view direction");
  TRY(readNumber(n, "fovy", c.fovyDegrees, 1.0, 179.0));
  TRY(readNumber(n, "near", c.nearPlane, 1e-6, 1e9));
  TRY(readNumber(n, "far", c.farPlane, 1e-6, 1e12));
  if (c.farPlane <= c.nearPlane) return n.error("far must be greater than near");
  std::string handedness = c.leftHanded ? "left" : "right";
  TRY(readEnum(n, "handedness", handedness, std::map<std::string, std::string>{{"left", "left"}, {"right", "right"}}));
  c.leftHanded = handedness == "left";
  return Ok{};
}

// A spot's file direction is the way it shines (straight down by default); the
// scene keeps the way toward the light (LightDesc::direction).
Status readSpotCone(const Node& n, LightDesc& l) {
  if (l.type != LightType::Spot) {
    for (const char* key : {"inner_cone", "outer_cone"}) {
      if (n.has(key)) return n.at(key).error("only a spot light has a cone");
    }
    return Ok{};
  }
  if (n.has("direction")) l.direction = -l.direction;
  TRY(readFloat(n, "outer_cone", l.outerConeDegrees, 0.0, 90.0));
  TRY(readFloat(n, "inner_cone", l.innerConeDegrees, 0.0, 90.0));
  if (l.innerConeDegrees > l.outerConeDegrees) {
    return n.at(n.has("inner_cone") ? "inner_cone" : "outer_cone").error("the inner cone must not be wider than the outer one");
  }
  return Ok{};
}

Status readLight(const Node& n, LightDesc& l) {
  TRY(n.expectObject({"type", "direction", "position", "color", "intensity", "falloff", "shadows", "u", "v", "angle",
                       "inner_cone", "outer_cone"}));
  if (!n.has("type")) return n.error("missing \"type\" (sun, point, spot or area)");
  TRY(readEnum(n, "type", l.type,
               std::map<std::string, LightType>{
                   {"sun", LightType::Sun}, {"point", LightType::Point}, {"spot", LightType::Spot}, {"area", LightType::Area}}));
  TRY(readDirection(n, "direction", l.direction));
  TRY(readSpotCone(n, l));
  TRY(readVec3(n, "position", l.position));
  TRY(readVec3(n, "color", l.color));
  TRY(readFloat(n, "intensity", l.intensity, 0.0, 1e9));
  TRY(readBool(n, "falloff", l.falloff));
  TRY(readBool(n, "shadows", l.shadows));
  TRY(readFloat(n, "angle", l.angleDegrees, 0.0, 20.0));
  TRY(readVec3(n, "u", l.edgeU));
  TRY(readVec3(n, "v", l.edgeV));
  if (l.type == LightType::Area && glm::length(glm::cross(l.edgeU, l.edgeV)) == 0.0) {
    return n.error("an area light needs two edges u and v that span a rectangle");
  }
  return Ok{};
}

Status readMaterial(const Node& n, MaterialDesc& m) {
  TRY(n.expectObject({"color", "ambient", "diffuse", "specular", "shininess", "reflection", "metallic", "roughness", "texture", "texture_scale", "emission"}));
  TRY(readVec3(n, "color", m.color));
  TRY(readFloat(n, "ambient", m.ambient, 0.0, 1.0));
  TRY(readFloat(n, "diffuse", m.diffuse, 0.0, 1.0));
  TRY(readFloat(n, "specular", m.specular, 0.0, 1.0));
  TRY(readFloat(n, "shininess", m.shininess, 1.0, 10000.0));
  TRY(readFloat(n, "reflection", m.reflection, 0.0, 1.0));
  TRY(readFloat(n, "metallic", m.metallic, 0.0, 1.0));
  TRY(readFloat(n, "roughness", m.roughness, 0.0, 1.0));
  TRY(readString(n, "texture", m.texture));
  TRY(readFloat(n, "texture_scale", m.textureScale, 1e-6, 1e6));
  TRY(readVec3(n, "emission", m.emission));
  if (glm::any(glm::lessThan(m.emission, glm::vec3(0.0f)))) return n.at("emission").error("emission must not be negative");
  return Ok{};
}

Status readPrimitive(const Node& n, PrimitiveDesc& p, const std::map<std::string, int>& materials) {
  TRY(n.expectObject({"type", "center", "radius", "point", "normal", "extent", "min", "max", "material"}));
  if (!n.has("type")) return n.error("missing \"type\" (sphere, plane or box)");
  TRY(readEnum(n, "type", p.type, std::map<std::string, PrimitiveType>{{"sphere", PrimitiveType::Sphere}, {"plane", PrimitiveType::Plane}, {"box", PrimitiveType::Box}}));
  TRY(readVec3(n, "center", p.center));
  TRY(readNumber(n, "radius", p.radius, 1e-9, 1e12));
  TRY(readVec3(n, "point", p.point));
  TRY(readDirection(n, "normal", p.normal));
  TRY(readNumber(n, "extent", p.extent, 0.0, 1e12));
  TRY(readVec3(n, "min", p.min));
  TRY(readVec3(n, "max", p.max));
  if (p.type == PrimitiveType::Box && !(p.min.x < p.max.x && p.min.y < p.max.y && p.min.z < p.max.z)) {
    return n.error("a box needs min < max on every axis");
  }
  std::string material;
  TRY(readString(n, "material", material));
  if (!material.empty()) {
    auto it = materials.find(material);
    if (it == materials.end()) return n.at("material").error("no material \"" + material + "\" in /materials");
    p.material = it->second;
  }
  return Ok{};
}

Status readModel(const Node& n, ModelDesc& m, const std::filesystem::path& folder) {
  TRY(n.expectObject({"path", "position", "rotation", "scale", "clip", "speed", "start", "skinning", "on_terrain"}));
  TRY(readBool(n, "on_terrain", m.onTerrain));
  if (!n.has("path")) return n.error("missing \"path\" of the glTF file");
  TRY(readString(n, "path", m.path));
  m.path = (folder / m.path).lexically_normal().string();
  TRY(readVec3(n, "position", m.position));
  TRY(readVec3(n, "rotation", m.rotationDegrees));
  if (n.has("scale") && n.at("scale").value().is_number()) {
    double s = 1.0;
    TRY(readNumber(n, "scale", s, 1e-9, 1e9));
    m.scale = glm::dvec3(s);
  } else {
    TRY(readVec3(n, "scale", m.scale));
  }
  if (n.has("clip") && n.at("clip").value().is_number_integer()) {
    m.clip = std::to_string(n.at("clip").value().get<long long>());
  } else {
    TRY(readString(n, "clip", m.clip));
  }
  TRY(readNumber(n, "speed", m.speed, -1e3, 1e3));
  TRY(readNumber(n, "start", m.start, -1e9, 1e9));
  std::string skinning = "lbs";
  TRY(readEnum(n, "skinning", skinning,
                std::map<std::string, std::string>{{"lbs", "lbs"}, {"dqs", "dqs"}, {"none", "none"}}));
  m.dualQuat = skinning == "dqs";
  m.unskinned = skinning == "none";
  return Ok{};
}

// The sky's image, checked here from its header (it must exist, be a Radiance .hdr
// or a PNG by its content, and have pixels) so that a bad one stops the scene before
// any renderer starts; the renderers decode it.
Status readSkyImage(const Node& n, SkyDesc& s, const std::filesystem::path& folder) {
  TRY(readString(n, "image", s.image));
  if (!n.has("image")) return Ok{};
  if (s.image.empty()) return n.at("image").error("expected the path of a .hdr or PNG image");
  s.image = (folder / s.image).lexically_normal().string();
  auto info = readHdrOrPngInfo(s.image);
  if (!info) return n.at("image").error(info.error().message);
  return Ok{};
}

Status readSky(const Node& n, SkyDesc& s, const std::filesystem::path& folder) {
  if (n.value().is_null() || (n.value().is_boolean() && !n.value().get<bool>())) {
    s.enabled = false;
    return Ok{};
  }
  TRY(n.expectObject({"zenith", "horizon", "ground", "sun_disk", "background", "enabled", "image", "intensity", "rotation"}));
  TRY(readSkyImage(n, s, folder));
  TRY(readFloat(n, "intensity", s.intensity, 0.0, 1e9));
  TRY(readFloat(n, "rotation", s.rotationDegrees, -360.0, 360.0));
  TRY(readBool(n, "enabled", s.enabled));
  TRY(readVec3(n, "zenith", s.zenith));
  TRY(readVec3(n, "horizon", s.horizon));
  TRY(readVec3(n, "ground", s.ground));
  TRY(readVec3(n, "background", s.background));
  TRY(readBool(n, "sun_disk", s.sunDisk));
  return Ok{};
}

}  // namespace

const std::map<std::string, Ambient>& ambientNames() {
  static const std::map<std::string, Ambient> names{
      {"hemisphere", Ambient::Hemisphere}, {"sh", Ambient::Sh}, {"ibl", Ambient::Ibl}};
  return names;
}

std::string ambientName(Ambient ambient) {
  for (const auto& [name, value] : ambientNames()) {
    if (value == ambient) return name;
  }
  return "?";
}

const std::map<std::string, Shading>& shadingNames() {
  static const std::map<std::string, Shading> names{{"classic", Shading::Classic}, {"pbr", Shading::Pbr}};
  return names;
}

const std::map<std::string, ToneMap>& toneMapNames() {
  static const std::map<std::string, ToneMap> names{
      {"none", ToneMap::None}, {"reinhard", ToneMap::Reinhard}, {"aces", ToneMap::Aces}};
  return names;
}

const std::map<std::string, OutputCurve>& outputNames() {
  static const std::map<std::string, OutputCurve> names{{"srgb", OutputCurve::Srgb}, {"gamma2.2", OutputCurve::Gamma22}};
  return names;
}

const std::map<std::string, Skinning>& skinningNames() {
  static const std::map<std::string, Skinning> names{
      {"vertex", Skinning::Vertex}, {"compute", Skinning::Compute}, {"auto", Skinning::Auto}};
  return names;
}

std::string skinningName(Skinning skinning) {
  for (const auto& [name, value] : skinningNames())
    if (value == skinning) return name;
  return "vertex";
}

namespace {

Status readRender(const Node& n, RenderDesc& r) {
  TRY(n.expectObject({"msaa", "supersample", "shading", "shadow_map", "shadow_filter", "pcf_kernel", "exposure", "tonemap", "output",
                          "reflection_probe", "ambient", "ibl_size", "skinning", "lod_pixels", "gpu_culling"}));
  TRY(readInt(n, "msaa", r.msaa, 1, 16));
  if (r.msaa & (r.msaa - 1)) return n.at("msaa").error("expected 1, 2, 4, 8 or 16");
  TRY(readInt(n, "supersample", r.supersample, 1, 4));
  TRY(readEnum(n, "shading", r.shading, shadingNames()));
  TRY(readInt(n, "shadow_map", r.shadowMapSize, 64, 8192));
  TRY(readEnum(n, "shadow_filter", r.shadowFilter, std::map<std::string, ShadowFilter>{{"hard", ShadowFilter::Hard}, {"pcf", ShadowFilter::Pcf}}));
  TRY(readInt(n, "pcf_kernel", r.pcfKernel, 1, 15));
  if (r.pcfKernel % 2 == 0) return n.at("pcf_kernel").error("expected an odd kernel width");
  TRY(readInt(n, "reflection_probe", r.reflectionProbe, 0, 2048));
  if (n.has("ambient")) {
    Ambient ambient = Ambient::Ibl;
    TRY(readEnum(n, "ambient", ambient, ambientNames()));
    r.ambient = ambient;
  }
  TRY(readInt(n, "ibl_size", r.iblSize, 16, 1024));
  TRY(readEnum(n, "skinning", r.skinning, skinningNames()));
  TRY(readNumber(n, "lod_pixels", r.lodPixels, 0.0, 64.0));
  TRY(readBool(n, "gpu_culling", r.gpuCulling));
  TRY(readFloat(n, "exposure", r.exposure, 1e-6, 1e6));
  TRY(readEnum(n, "tonemap", r.toneMap, toneMapNames()));
  TRY(readEnum(n, "output", r.output, outputNames()));
  return Ok{};
}

Status readTerrain(const Node& n, TerrainDesc& t, const std::filesystem::path& folder) {
  TRY(n.expectObject({"heightmap", "seed", "size", "height_scale", "spacing", "error_pixels", "origin"}));
  t.enabled = true;
  TRY(readString(n, "heightmap", t.heightmap));
  if (!t.heightmap.empty()) t.heightmap = (folder / t.heightmap).lexically_normal().string();
  int seed = int(t.seed);
  TRY(readInt(n, "seed", seed, 0, 1 << 30));
  t.seed = unsigned(seed);
  TRY(readNumber(n, "size", t.size, 1e-3, 1e7));
  TRY(readNumber(n, "height_scale", t.heightScale, 0.0, 1e6));
  TRY(readNumber(n, "spacing", t.spacing, 1e-3, 1e4));
  TRY(readNumber(n, "error_pixels", t.errorPixels, 0.1, 100.0));
  TRY(readVec3(n, "origin", t.origin));
  return Ok{};
}

template <typename T, typename F>
Status readArray(const Node& root, const char* key, std::vector<T>& out, F&& readOne) {
  if (!root.has(key)) return Ok{};
  const Node arr = root.at(key);
  auto size = arr.arraySize();
  if (!size) return size.error();
  for (size_t i = 0; i < *size; ++i) {
    T item;
    TRY(readOne(arr.at(i), item));
    out.push_back(std::move(item));
  }
  return Ok{};
}

}  // namespace

glm::dvec3 CameraDesc::right() const {
  return glm::normalize(leftHanded ? glm::cross(up, forward) : glm::cross(forward, up));
}

Result<SceneDesc> parseScene(const std::string& text, const std::string& name) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    // Its line and column, or the number too large for a double (1e999: no JSON
    // number is infinite, so a non-finite coefficient ends here).
    return makeError(name + ": not valid JSON: " + e.what());
  }
  const Node root(j, name, "");
  TRY(root.expectObject({"camera", "lights", "materials", "primitives", "models", "sky", "fog", "atmosphere", "media", "terrain", "render", "ambient", "comment"}));
  SceneDesc scene;
  scene.path = name;
  const auto folder = std::filesystem::path(name).parent_path();
  if (root.has("camera")) TRY(readCamera(root.at("camera"), scene.camera));
  TRY(readArray(root, "lights", scene.lights, readLight));

  // Materials are an object of name -> material; primitives refer to them by name.
  std::map<std::string, int> materialIndex;
  MaterialDesc fallback;
  fallback.name = "default";
  scene.materials.push_back(fallback);
  materialIndex["default"] = 0;
  if (root.has("materials")) {
    const Node mats = root.at("materials");
    if (!mats.value().is_object()) return mats.error("expected an object of name: material");
    for (const auto& item : mats.value().items()) {
      MaterialDesc m;
      m.name = item.key();
      TRY(readMaterial(mats.at(item.key().c_str()), m));
      if (materialIndex.count(m.name)) {
        scene.materials[size_t(materialIndex[m.name])] = m;
      } else {
        materialIndex[m.name] = int(scene.materials.size());
        scene.materials.push_back(m);
      }
    }
  }
  TRY(readArray(root, "primitives", scene.primitives,
                [&](const Node& n, PrimitiveDesc& p) { return readPrimitive(n, p, materialIndex); }));
  TRY(readArray(root, "models", scene.models,
                [&](const Node& n, ModelDesc& m) { return readModel(n, m, folder); }));
  if (root.has("sky")) TRY(readSky(root.at("sky"), scene.sky, folder));
  if (root.has("fog")) TRY(readFog(root.at("fog"), scene.fog));
  if (root.has("atmosphere")) TRY(readAtmosphere(root.at("atmosphere"), scene.atmosphere));
  TRY(readArray(root, "media", scene.media, readMedium));
  if (root.has("terrain")) TRY(readTerrain(root.at("terrain"), scene.terrain, folder));
  if (root.has("render")) TRY(readRender(root.at("render"), scene.render));
  TRY(readFloat(root, "ambient", scene.ambient, 0.0, 1.0));
  return scene;
}

Result<SceneDesc> loadSceneFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return makeError(path + ": cannot open scene file");
  std::ostringstream ss;
  ss << in.rdbuf();
  // Scene files are small; a huge one is a mistake, not a scene.
  if (ss.str().size() > (64u << 20)) return makeError(path + ": scene file larger than 64 MiB");
  return parseScene(ss.str(), path);
}

}  // namespace engine
