#pragma once
// The ray tracer's material table: the scene's MaterialDesc list with what each
// material has beyond it (textures, the terrain's layers, glTF's alpha, sidedness,
// unlit), and what a hit on a material shades with (HitMaterial), evaluated at its
// texture coordinates. GL-free; the GPU tracer copies it (gputrace/gpu_materials.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "asset/model_data.h"
#include "asset/scene_desc.h"
#include "core/brdf.h"
#include "core/layer_texels.h"
#include "core/result.h"
#include "core/sheen_table.h"
#include "core/view_layers.h"
#include "raytrace/terrain_material.h"
#include "raytrace/texture.h"
#include "scene/materials.h"

namespace engine::rt {

// What layeredBrdf (core/brdf.h) takes of a hit's layers that depends on the view:
// the sheen's albedo E and the scaling it leaves the base, the anisotropic frame
// about the shading normal (anisotropy 0 where there is none to orient), and the
// thin film's Fresnel. HitMaterial::atView works them out once per hit, for the
// Whitted tracer's lights and ambient and for the path tracer's Bsdf alike, by
// common/view_layers.glsl, the GPU tracers' text (core/view_layers.h). Made empty:
// no sheen, no stretch, no film.
struct ViewLayers : brdf::ViewLayers {
  ViewLayers() : brdf::ViewLayers{0.0f, 1.0f, glm::vec3(0.0f), glm::vec3(0.0f), 0.0f, glm::vec3(0.0f)} {}
  ViewLayers(const brdf::ViewLayers& v) : brdf::ViewLayers(v) {}  // NOLINT(google-explicit-constructor)
};

// What the integrator shades one hit with: its material's weights, with the albedo
// (colour times texture) and, for the terrain's layered material, the roughness and
// highlight evaluated at the hit.
struct HitMaterial {
  glm::vec3 albedo{0.8f};
  float ambient = 0.1f, diffuse = 0.9f, specular = 0.0f, shininess = 32.0f, reflection = 0.0f;
  float metallic = 0.0f, roughness = 0.6f;
  glm::vec3 emission{0.0f};
  // KHR_materials_unlit: the surface sends its albedo (base colour) back as it is
  // and scatters nothing; the tracers stop there.
  bool unlit = false;
  // Metallic-roughness: the dielectric's f0 and f90 and the clear coat
  // (asset/material_layers.h; layeredBrdf in core/brdf.h).
  glm::vec3 dielectricF0{0.04f};
  float dielectricF90 = 1.0f;
  float clearcoat = 0.0f, clearcoatRoughness = 0.0f;
  // KHR_materials_transmission and _volume (asset/material_layers.h): the share of
  // the diffuse lobe passed through, the ior it bends by, the volume's thickness
  // (0: a thin wall) and its absorption.
  float transmission = 0.0f;
  float ior = 1.5f;
  float thickness = 0.0f;
  float attenuationDistance = 0.0f;
  glm::vec3 attenuationColor{1.0f};
  // KHR_materials_sheen (asset/material_layers.h): the fibres' colour and roughness.
  glm::vec3 sheenColor{0.0f};
  float sheenRoughness = 0.0f;
  // KHR_materials_anisotropy: the stretch's strength and turn, the direction in the
  // tangent frame its texture gives (+x without one), and the stretch's direction in
  // world space at the hit (RtScene::materialAt; zero where the hit has no uv
  // gradient to orient it by, and then no stretch).
  float anisotropy = 0.0f;
  float anisotropyRotation = 0.0f;
  glm::vec2 anisotropyDirection{1.0f, 0.0f};
  glm::vec3 anisotropyT{0.0f};
  // KHR_materials_iridescence: the thin film's share, index and thickness (nm) at the
  // hit, and its Fresnel at N.V over this base (brdf.glsl's iridescenceFresnel).
  float iridescence = 0.0f;
  float iridescenceIor = 1.3f;
  float iridescenceThickness = 400.0f;
  glm::vec3 iridescenceFresnelAt(float nDotV) const {
    return brdf::iridescenceFresnel(1.0f, iridescenceIor, nDotV, iridescenceThickness,
                                    glm::mix(dielectricF0, albedo, metallic));
  }
  // The white sheen's directional albedo at N.V (core/sheen_table.h); 0 without one.
  float sheenAlbedo(float nDotV) const {
    return sheenColor != glm::vec3(0.0f) ? sheenTable().lookup(nDotV, sheenRoughness) : 0.0f;
  }
  // The view's terms (ViewLayers) for the unit shading normal n at N.V = nDotV: the
  // stretch made orthogonal to n (the tracers' lobe is stretched along it, across it
  // along n x it), the film's Fresnel at N.V no less than 1e-4.
  ViewLayers atView(const glm::vec3& n, float nDotV) const {
    return brdf::viewLayersOf(n, nDotV, sheenAlbedo(nDotV), sheenColor, anisotropyT, anisotropy, iridescence,
                              iridescenceIor, iridescenceThickness, dielectricF0, albedo, metallic);
  }
};

// What a material has beyond its MaterialDesc: textures (indices into textures_,
// -1 none), the terrain's layers (into terrains_) and glTF's alpha.
struct MaterialExtras {
  int texture = -1;
  int emissiveTexture = -1;
  int metallicRoughnessTexture = -1;
  std::array<int, kTextureSlots - kFirstLayerSlot> layerTextures{-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1};
  // MaterialDesc::layers' dielectric f0 (worked in double), once per material, not per hit.
  glm::vec3 dielectricF0{0.04f};
  // Kept as layer textures are attached, not searched for among the twelve slots
  // at every hit.
  bool hasLayerTextures = false;
  // Whether anything at a hit reads its texture coordinates (a texture or the
  // terrain's layers): an analytic shape's are worked out (in double, through acos
  // and atan2 on a sphere) only then.
  bool readsUv() const {
    return texture >= 0 || emissiveTexture >= 0 || metallicRoughnessTexture >= 0 || terrain >= 0 || hasLayerTextures;
  }
  bool singleSided = false;
  bool unlit = false;
  int terrain = -1;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alpha = 1.0f;
  float alphaCutoff = 0.5f;
};

class RtMaterials {
 public:
  RtMaterials();  // one default material
  // The scene file's materials as they are, nothing attached to them yet (their
  // MaterialExtras at the defaults, as RtScene::fromSceneDesc has always made them).
  explicit RtMaterials(std::vector<MaterialDesc> materials);

  int addMaterial(const MaterialDesc& material);
  // A material of the scene layer's table (scene/materials.h): its surface, then
  // what setSceneMaterial attaches.
  Result<int> addSceneMaterial(const SceneMaterial& material);
  // Gives `material` the rest of a table entry: its textures (the tracers read no
  // normal map, nor the coat's, nor occlusion), glTF's alpha, one-sidedness and unlit.
  Status setSceneMaterial(int material, const SceneMaterial& from);
  // An error naming the material when it is out of range.
  Status checkMaterial(int material) const;
  // A base colour texture that multiplies `material`'s colour (the rasterizer's
  // baseColorFactor * texture(uv)); the material's meshes need uvs to show it.
  Status setMaterialTexture(int material, RtTexture texture);
  // glTF's alpha: `factor` times the base colour texture's alpha. MASK removes the
  // surface where that is below `cutoff`; BLEND makes it that opaque.
  Status setMaterialAlpha(int material, AlphaMode mode, float factor, float cutoff);
  // Multiplies the material's emission (glTF's emissiveTexture; sRGB decoded).
  Status setEmissiveTexture(int material, RtTexture texture);
  // glTF's metallicRoughnessTexture (linear): roughness times G, metallic times B.
  Status setMetallicRoughnessTexture(int material, RtTexture texture);
  // glTF's single-sided materials: the rasterizer culls their back faces, so rays
  // pass through them from behind (the path tracer; shadows still fall).
  Status setSingleSided(int material, bool singleSided);
  // KHR_materials_unlit (HitMaterial::unlit).
  Status setUnlit(int material, bool unlit);
  // One of glTF's layer textures (`slot` Specular .. IridescenceThickness): they scale the
  // material's MaterialLayers at each hit (specular by A, its colour by RGB, the coat
  // by R, its roughness by G, transmission by R, thickness by G, the sheen's colour
  // by RGB and its roughness by A, anisotropy's direction by RG and strength by B,
  // iridescence by R and the film's thickness by G between its minimum and maximum).
  Status setLayerTexture(int material, TextureSlot slot, RtTexture texture);
  bool singleSided(int material) const { return extras_[size_t(material)].singleSided; }
  // How much of a ray the surface stops at uv: 1 opaque, 0 cut away (MASK), or
  // BLEND's alpha; the path tracer lets the rest through.
  float opacityAt(int material, const HitUv& uv, float footprint = 0.0f) const;
  // opacityAt for a hit seen from the back (`backFacing`) or the front: 0 for a
  // single-sided material seen from behind, which the rasterizer culls.
  float surfaceOpacity(int material, const HitUv& uv, float footprint, bool backFacing) const {
    return backFacing && singleSided(material) ? 0.0f : opacityAt(material, uv, footprint);
  }
  // Whether any material is not opaque (else shadow rays need no more than any hit).
  bool hasTransparency() const { return transparent_; }
  // Whether any material is single-sided (rays may pass its back faces).
  bool hasSingleSided() const { return singleSided_; }
  // Whether any material reads a texture (base colour, emissive, metallic-roughness)
  // or the terrain's layers.
  bool hasTextures() const {
    return std::any_of(extras_.begin(), extras_.end(), [](const MaterialExtras& e) { return e.readsUv(); });
  }
  // Makes `material` the terrain's layers: its albedo (times its colour), roughness
  // and specular come from `layers` at each hit's uv, height and shading normal.
  Status setTerrainMaterial(int material, RtTerrainMaterial layers);
  // The material's own weights, before any texture, vertex colour or terrain layer
  // (what materialAt starts from; the GPU tracer applies the rest in its shaders).
  HitMaterial baseMaterial(int material) const;
  // The material at a hit with uv `uv` (and `footprint`, as RtTexture::sample takes
  // it), world height `y` and unit shading normal `ns`.
  // `dpdu` and `dpdv` (SurfaceInteraction's) orient KHR_materials_anisotropy.
  HitMaterial materialAt(int material, const HitUv& uv, float footprint, double y, const glm::vec3& ns,
                         const glm::vec3& dpdu = glm::vec3(0.0f), const glm::vec3& dpdv = glm::vec3(0.0f)) const;

  const std::vector<MaterialDesc>& materials() const { return materials_; }
  const MaterialExtras& extras(int material) const { return extras_[std::size_t(material)]; }
  // The textures materials point at (MaterialExtras' indices) and the terrains'
  // layered materials: what the GPU tracer copies (gputrace/gpu_textures.h).
  const std::vector<RtTexture>& textures() const { return textures_; }
  const std::vector<RtTerrainMaterial>& terrains() const { return terrains_; }

 private:
  Status attachTexture(int material, int MaterialExtras::*slot, RtTexture texture);
  brdf::BaseValues baseAt(int material, const HitUv& uv, float footprint) const;
  void applyLayerTextures(int material, const HitUv& uv, float footprint, HitMaterial& out) const;

  std::vector<MaterialDesc> materials_;
  std::vector<MaterialExtras> extras_;  // one per material
  bool transparent_ = false;
  bool singleSided_ = false;
  std::vector<RtTexture> textures_;
  std::vector<RtTerrainMaterial> terrains_;
};

}  // namespace engine::rt
