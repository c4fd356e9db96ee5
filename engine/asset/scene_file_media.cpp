// The scene file's media: "fog", "atmosphere" and "media" (docs/scene-format.md).
#include "asset/scene_file_node.h"

namespace engine::scenefile {

Status readCoefficients(const Node& parent, const char* key, glm::vec3& out) {
  TRY(readVec3(parent, key, out));
  for (int i = 0; i < 3; ++i) {
    if (out[i] < 0.0f || out[i] > 1e6f) return parent.at(key).at(size_t(i)).error("expected a number in [0, 1e6] per metre");
  }
  return Ok{};
}

// A Henyey-Greenstein g: |g| = 1 is a delta, which no phase sampling can draw.
static Status readAnisotropy(const Node& n, float& g) { return readFloat(n, "anisotropy", g, -0.999, 0.999); }

Status readFog(const Node& fog, FogDesc& out) {
  TRY(fog.expectObject({"density", "color", "model", "scattering", "absorption", "anisotropy", "height_falloff"}));
  out.enabled = true;
  TRY(readEnum(fog, "model", out.model,
               std::map<std::string, FogModel>{{"exponential", FogModel::Exponential}, {"volumetric", FogModel::Volumetric}}));
  TRY(readVec3(fog, "color", out.color));
  if (out.model == FogModel::Exponential) {
    for (const char* key : {"scattering", "absorption", "anisotropy", "height_falloff"}) {
      if (fog.has(key)) return fog.at(key).error("only a volumetric fog (\"model\": \"volumetric\") has it");
    }
    return readFloat(fog, "density", out.density, 0.0, 100.0);
  }
  if (fog.has("density")) return fog.at("density").error("a volumetric fog takes scattering and absorption instead");
  out.scattering = glm::vec3(0.02f);
  TRY(readCoefficients(fog, "scattering", out.scattering));
  TRY(readCoefficients(fog, "absorption", out.absorption));
  TRY(readAnisotropy(fog, out.anisotropy));
  // Past 1 per metre the fog would halve within a metre of height: a wall, not a fog.
  TRY(readFloat(fog, "height_falloff", out.heightFalloff, 0.0, 1.0));
  const glm::vec3 extinction = out.scattering + out.absorption;
  out.density = (extinction.x + extinction.y + extinction.z) / 3.0f;  // the stand-in's
  return Ok{};
}

// Scale heights and the ozone layer's shape, in metres: from a metre (a scale height
// of zero would be a wall) to a thousand kilometres.
static Status readHeight(const Node& n, const char* key, float& out) { return readFloat(n, key, out, 1.0, 1e6); }

static Status readRayleigh(const Node& r, AtmosphereDesc& a) {
  TRY(r.expectObject({"scattering", "scale_height"}));
  TRY(readCoefficients(r, "scattering", a.rayleighScattering));
  return readHeight(r, "scale_height", a.rayleighScaleHeight);
}

static Status readMie(const Node& m, AtmosphereDesc& a) {
  TRY(m.expectObject({"scattering", "absorption", "scale_height", "anisotropy"}));
  TRY(readCoefficients(m, "scattering", a.mieScattering));
  TRY(readCoefficients(m, "absorption", a.mieAbsorption));
  TRY(readHeight(m, "scale_height", a.mieScaleHeight));
  return readAnisotropy(m, a.mieAnisotropy);
}

static Status readOzone(const Node& o, AtmosphereDesc& a) {
  TRY(o.expectObject({"absorption", "center", "half_width"}));
  TRY(readCoefficients(o, "absorption", a.ozoneAbsorption));
  TRY(readFloat(o, "center", a.ozoneCenter, 0.0, 1e6));
  return readHeight(o, "half_width", a.ozoneHalfWidth);
}

Status readAtmosphere(const Node& n, AtmosphereDesc& a) {
  TRY(n.expectObject({"planet_radius", "thickness", "rayleigh", "mie", "ozone", "ground_albedo", "comment"}));
  a.enabled = true;
  // From an asteroid's kilometre to well past Jupiter's 70 000 km.
  TRY(readNumber(n, "planet_radius", a.planetRadius, 1e3, 1e9));
  TRY(readNumber(n, "thickness", a.thickness, 1.0, 1e8));
  if (n.has("rayleigh")) TRY(readRayleigh(n.at("rayleigh"), a));
  if (n.has("mie")) TRY(readMie(n.at("mie"), a));
  if (n.has("ozone")) TRY(readOzone(n.at("ozone"), a));
  TRY(readVec3(n, "ground_albedo", a.groundAlbedo));
  for (int i = 0; i < 3; ++i) {
    if (a.groundAlbedo[i] < 0.0f || a.groundAlbedo[i] > 1.0f) {
      return n.at("ground_albedo").at(size_t(i)).error("expected an albedo in [0, 1]");
    }
  }
  return Ok{};
}

Status readMedium(const Node& n, MediumDesc& m) {
  TRY(n.expectObject({"type", "min", "max", "scattering", "absorption", "anisotropy", "comment"}));
  if (!n.has("type")) return n.error("missing \"type\" (box)");
  std::string type;
  TRY(readEnum(n, "type", type, std::map<std::string, std::string>{{"box", "box"}}));
  for (const char* key : {"min", "max"}) {
    if (!n.has(key)) return n.error(std::string("a box medium needs \"") + key + "\"");
  }
  TRY(readVec3(n, "min", m.min));
  TRY(readVec3(n, "max", m.max));
  for (int i = 0; i < 3; ++i) {
    if (!(m.min[i] < m.max[i])) return n.at("max").at(size_t(i)).error("a box's max must be greater than its min");
  }
  TRY(readCoefficients(n, "scattering", m.scattering));
  TRY(readCoefficients(n, "absorption", m.absorption));
  return readAnisotropy(n, m.anisotropy);
}

}  // namespace engine::scenefile
