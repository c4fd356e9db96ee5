#pragma once
// What the ray tracer traces: analytic spheres and planes, triangle meshes in world
// space, lights, materials, camera and sky. Built from the SceneDesc the rasterizer
// also reads; the caller adds meshes (skinned characters, terrain) and, per frame,
// moves their vertices and calls refit() (or build() when triangles change).
//
// Two levels: meshes belong to groups, each group has its own BVH, and a ray visits
// every group whose bounds it crosses. Group 0 holds the static world (boxes, the
// 1.3M-triangle terrain), built once; each character gets a group of its own, so a
// new pose refits that character's BVH (its vertices move, its triangles stay) and
// never touches the terrain's. A linear top level suits the few groups a scene has
// (the demo: 5); hundreds of instances would want a BVH over the groups.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "asset/model_data.h"
#include "asset/scene_desc.h"
#include "core/brdf.h"
#include "core/result.h"
#include "core/sheen_table.h"
#include "core/view_layers.h"
#include "raytrace/bvh.h"
#include "raytrace/environment.h"
#include "raytrace/ray.h"
#include "raytrace/shape_lanes.h"
#include "scene/scene_images.h"
#include "raytrace/shape_packs.h"
#include "raytrace/shapes.h"
#include "raytrace/terrain_material.h"
#include "raytrace/texture.h"

namespace engine::rt {

// A triangle mesh in world space. Normals are optional (empty: flat shading from the
// triangle's own normal); when present there is one per position.
struct RtMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;  // empty, or one per position (glTF TEXCOORD_0)
  std::vector<glm::vec2> uvs1;  // empty (hits take uvs), or one per position (TEXCOORD_1)
  std::vector<glm::vec4> colors;  // empty (white), or one per position (COLOR_0, linear RGBA)
  std::vector<std::uint32_t> indices;  // three per triangle
  int material = 0;
  int group = 0;  // the BVH it lives in: 0 the static world, or one from addGroup()
};

using MeshId = int;

// What the integrator shades one hit with: its material's weights, with the albedo
// (colour times texture) and, for the terrain's layered material, the roughness and
// highlight evaluated at the hit.
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

class RtScene {
 public:
  RtScene();  // one default material, no shapes, no lights, the default camera
  // Spheres, planes, boxes (as 12 triangles each), lights, materials, camera, sky and
  // render settings. Models and terrain are the caller's to add as meshes.
  // The scene file's textures and sky image come decoded (scene/scene_images.h).
  static Result<RtScene> fromSceneDesc(const SceneDesc& desc, const SceneImages& images);

  int addMaterial(const MaterialDesc& material);
  // A base colour texture that multiplies `material`'s colour (the rasterizer's
  // baseColorFactor * texture(uv)); the material's meshes need uvs to show it.
  Status setMaterialTexture(int material, RtTexture texture);
  // The material's colour times its texture at the hit's uv, linear RGB; `footprint`
  // as RtTexture::sample takes it.
  glm::vec3 baseColor(int material, const HitUv& uv, float footprint = 0.0f) const;
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
  // A sun also draws the gradient sky's disk, as the last sun did before.
  void addLight(const LightDesc& light);
  void addSphere(const glm::dvec3& center, double radius, int material);
  // `extent`: the half size of the square the rasterizer draws; hits beyond it miss,
  // and it sets the plane's texture coordinates. 0: an unbounded plane.
  void addPlane(const glm::dvec3& point, const glm::dvec3& normal, int material, double extent = 0.0);
  void setCamera(const CameraDesc& camera) { camera_ = camera; }
  // The sky's gradient (with the last sun light's disk) or background colour. An
  // image sky is not loaded here, as loading can fail: build it with
  // Environment::create and give it to setEnvironment.
  void setSky(const SkyDesc& sky);
  // What escaping rays see from now on, whatever the sky and the lights say.
  void setEnvironment(Environment environment);
  void setRender(const RenderDesc& render) { render_ = render; }
  void setFog(const FogDesc& fog) { fog_ = fog; }

  // A new, empty BVH group for meshes that move together (one character), or that
  // rays meet apart from the rest (raytrace/ground_split.h). `name`: what --describe
  // calls it.
  int addGroup(std::string name = {});
  // Group 0 is "static".
  std::string groupName(int group) const { return group == 0 ? "static" : groups_[std::size_t(group)].name; }
  // Validates the mesh (indices in range, one normal per position, a known material
  // and group); its group's BVH is rebuilt at the next build() or refit().
  Result<MeshId> addMesh(RtMesh mesh);
  // New vertex positions (and normals, if the mesh has them) for the same triangles.
  Status updateMesh(MeshId id, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals = {});
  void clearMeshes();

  // Rebuilds every group's BVH with the SAH; returns the seconds it took.
  double build();
  // Refits the BVH of each group whose meshes moved (updateMesh) and builds those
  // that gained meshes since their last build; returns the seconds it took.
  double refit();
  // The same for one group (the per-character figures of the benchmark).
  double buildGroup(int group);
  double refitGroup(int group);

  // The nearest hit in (0, ray.tMax) over every shape, and whether any hit exists.
  template <typename T>
  std::optional<SurfaceInteraction<T>> intersect(const Ray<T>& ray) const;
  // intersect() of each of several float rays (a batch of paths, a bounce at a time),
  // the same answers bit for bit; the spheres and planes meet four or eight rays at a
  // time.
  void intersectMany(const Ray<float>* const* rays, std::size_t count,
                     std::optional<SurfaceInteraction<float>>* out) const;
  // intersect() of eight coherent float rays (a camera's row of eight pixels): each
  // ray's spheres and planes on its own, then each group's BVH for the rays that enter
  // its box, together (Bvh::intersect8). The same nearest hits bit for bit, but that
  // of triangles at exactly the same distance either may be named, and that a
  // triangle an ulp or two before the nearest hit so far, behind a box whose entry the
  // ray alone rounds to that hit's distance, may be found (the packet's interval box
  // test enters it): a crate's floor on the plaza, from inside the crate.
  void intersectCoherent(std::span<const Ray<float>, Bvh::kPacketSize> rays,
                         std::span<std::optional<SurfaceInteraction<float>>, Bvh::kPacketSize> out) const;
  // Whether intersectMany takes eight rays to a pass (no triangles, and AVX2) rather
  // than four.
  bool eightRaysAtATime() const { return !boxedTriangles_ && lanes_.size() > 0 && cpuHasAvx2(); }
  template <typename T>
  bool intersectAny(const Ray<T>& ray) const;
  // The share of light that passes along a shadow ray: 0 or 1 past opaque surfaces
  // (an any-hit ray), the product of 1 - opacity past cut-away and transparent ones
  // (exact, not stochastic). `target`: the ray ends there (d = target - o, tMax 1);
  // null: it goes to tMax along d. `rays` counts the rays traced.
  template <typename T>
  float transmittance(const Ray<T>& ray, const Vec3<T>* target, std::uint64_t& rays) const;

  const CameraDesc& camera() const { return camera_; }
  const std::vector<LightDesc>& lights() const { return lights_; }
  const std::vector<MaterialDesc>& materials() const { return materials_; }
  const SkyDesc& sky() const { return sky_; }
  const Environment& environment() const { return environment_; }
  // PBR's hemisphere ambient (see ambientSkyColor in asset/scene_desc.h).
  glm::vec3 ambientSky() const { return ambientSky_; }
  glm::vec3 ambientGround() const { return ambientGround_; }
  const RenderDesc& render() const { return render_; }
  const FogDesc& fog() const { return fog_; }
  // The rasterizer's distance fog (shaders/scene.frag, common/fog.glsl) on a colour the
  // camera sees at `distance`: mix(fog colour, colour, exp(-density * distance)). It
  // is the scene's look, not a medium: no light scatters in it, in either tracer.
  glm::vec3 fogged(const glm::vec3& color, float distance) const {
    if (!fog_.enabled) return color;
    return glm::mix(fog_.color, color, std::clamp(std::exp(-fog_.density * distance), 0.0f, 1.0f));
  }
  const std::vector<RtMesh>& meshes() const { return meshes_; }
  int groupCount() const { return int(groups_.size()); }
  const Bvh& bvh(int group = 0) const { return groups_[std::size_t(group)].bvh; }
  std::size_t triangleCount() const;
  // What raytrace/gpu_layout.h flattens for the GPU: the float shapes, each plane's
  // square (onPlaneSquare), and which mesh each of a group's triangles comes from
  // (the BVH's triangle index is its place in its group, meshes in group order).
  const std::vector<Sphere<float>>& floatSpheres() const { return spheresF_; }
  const std::vector<Plane<float>>& floatPlanes() const { return planesF_; }
  using PlaneSquare = rt::PlaneSquare;
  const PlaneSquare& planeSquare(std::size_t plane) const { return planeUvs_[plane]; }
  const std::vector<std::uint32_t>& groupTriangleMeshes(int group) const {
    return groups_[std::size_t(group)].triangleMesh;
  }
  std::uint32_t meshFirstTriangle(MeshId mesh) const { return meshFirstTriangle_[std::size_t(mesh)]; }
  std::size_t sphereCount() const { return spheresF_.size(); }
  // The spheres and planes as the eight-lane kernels read them (shape_lanes.h).
  const ShapeLanes& shapeLanes() const { return lanes_; }
  std::size_t planeCount() const { return planesF_.size(); }

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
  const MaterialExtras& extras(int material) const { return extras_[std::size_t(material)]; }
  // The textures materials point at (MaterialExtras' indices) and the terrains'
  // layered materials: what the GPU tracer copies (raytrace/gpu_textures.h).
  const std::vector<RtTexture>& textures() const { return textures_; }
  const std::vector<RtTerrainMaterial>& terrains() const { return terrains_; }

 private:
  template <typename T>
  const std::vector<Sphere<T>>& spheres() const;
  template <typename T>
  const std::vector<Plane<T>>& planes() const;
  struct Group;
  template <typename T>
  SurfaceInteraction<T> meshInteraction(const Group& group, const BvhHit<T>& hit) const;
  template <typename T>
  bool onPlaneSquare(std::size_t plane, const Ray<T>& ray, T t) const;
  // The nearest sphere and plane hits (kind 1 or 2, or 0) with ray.tMax shortened to
  // them, and whether any exists: four shapes at a time for float rays, one at a time
  // for double.
  // `testSpheres` false: the ray misses every sphere (RootHits::spheres), none is tested.
  template <typename T>
  int nearestShape(Ray<T>& ray, std::size_t& index, bool testSpheres = true) const;
  template <typename T>
  bool anyShape(const Ray<T>& ray, bool testSpheres = true) const;
  // nearestShape of eight float rays at once, a ray to a lane (lanes8::Shapes::nearest,
  // the same bits; every sphere tested, since the spheres' root box only ever skips
  // spheres a ray misses). AVX2 only.
  void nearestShapesOfEight(Ray<float>* rays, int* kind, std::size_t* index) const;
  // The groups' root boxes and the spheres' box side by side as one 8-wide BVH node,
  // tested once per float ray (Bvh::testBoxes, all at once) in place of a scalar box
  // test per group, and so that rays that miss every sphere test none: lane g is
  // group g's root box, the last lane a box around the spheres, widened so that every
  // hit the float sphere test finds lies within it. Used when there are at most seven
  // groups; remade whenever a group's tree or the spheres change.
  static constexpr int kSphereLane = Bvh::kWidth - 1;
  struct RootHits {
    int mask = 0;
    alignas(32) float tEntry[Bvh::kWidth];
    // Group g's box entered before tMax: the scalar intersectBounds' answer.
    bool group(std::size_t g, float tMax) const { return (mask >> g & 1) && tEntry[g] < tMax; }
    bool spheres() const { return (mask >> kSphereLane & 1) != 0; }
  };
  bool rootsUsable() const { return groups_.size() <= std::size_t(kSphereLane); }
  RootHits testRoots(const Ray<float>& ray) const;
  // The same into `hits` in place (an array's element: assigning one returned read
  // it back in 16-byte loads over the mask's 4-byte store, a store-forwarding stall).
  void testRoots(const Ray<float>& ray, RootHits& hits) const;
  void updateRoots();
  // intersect() once the spheres and planes have shortened ray.tMax to their nearest
  // (kind 1 or 2 at `index`, 0 none): the meshes, then the winner's interaction,
  // written into `result` where it is kept (a record returned was copied). `roots`:
  // the ray's RootHits at its tMax before the shapes, when the caller has them.
  template <typename T>
  void pastShapes(Ray<T>& ray, int kind, std::size_t index, std::optional<SurfaceInteraction<T>>& result,
                  const RootHits* roots = nullptr) const;
  // The hit record of the sphere (kind 1) or plane (2) at `index` that `ray` meets at
  // ray.tMax; nothing for kind 0.
  template <typename T>
  void shapeInteraction(const Ray<T>& ray, int kind, std::size_t index, std::optional<SurfaceInteraction<T>>& result) const;
  // The rest of a sphere's (kind 1) or plane's (2) hit record once fillInteraction has
  // made it: texture coordinates where its material reads them, their scale per metre.
  template <typename T>
  void shapeUv(int kind, std::size_t index, SurfaceInteraction<T>& si) const;
  // intersectMany of up to eight rays in a scene without triangles, in one AVX2 pass
  // over the shapes (shape_lanes.h).
  void intersectEight(const Ray<float>* const* rays, int count, std::optional<SurfaceInteraction<float>>* out) const;
  // onPlaneSquare as ShapePacks asks it.
  static bool onSquareOf(const void* scene, std::size_t plane, const Ray<float>& ray, float t);
  Status checkMaterial(int material) const;  // an error naming it when out of range
  Status attachTexture(int material, int MaterialExtras::*slot, RtTexture texture);
  void applyLayerTextures(int material, const HitUv& uv, float footprint, HitMaterial& out) const;
  void gatherTriangles(int group);

  CameraDesc camera_;
  std::vector<LightDesc> lights_;
  std::vector<MaterialDesc> materials_;
  std::vector<MaterialExtras> extras_;  // one per material
  bool transparent_ = false;
  bool singleSided_ = false;
  std::vector<RtTexture> textures_;
  std::vector<RtTerrainMaterial> terrains_;
  // Per plane, its square and what its texture coordinates need: the rasterizer
  // draws it as a square of half size `extent` (0: unbounded) rotated from +y to its
  // normal, with uv = (local + extent) * texture scale along that square's x and z.
  using PlaneUv = PlaneSquare;
  std::vector<PlaneUv> planeUvs_;
  // The sun whose disk the gradient sky draws: the last sun light, as the
  // integrator chose it before the environment existed.
  std::optional<glm::vec3> sunDirection() const;
  void rebuildGradientSky();

  SkyDesc sky_;
  Environment environment_;
  // Whether environment_ follows sky_ and the lights (false after setEnvironment).
  bool environmentFromSky_ = true;
  glm::vec3 ambientSky_{0.1f};
  glm::vec3 ambientGround_{0.1f};
  RenderDesc render_;
  FogDesc fog_;
  // Each analytic shape in both precisions, so neither path converts per ray.
  std::vector<Sphere<float>> spheresF_;
  std::vector<Sphere<double>> spheresD_;
  std::vector<Plane<float>> planesF_;
  std::vector<Plane<double>> planesD_;
  // The float shapes again, four to a pack, for float rays (shape_packs.h), and as
  // one table for eight rays at once (shape_lanes.h).
  ShapePacks packs_;
  ShapeLanes lanes_;

  struct Group {
    std::string name;
    std::vector<std::uint32_t> meshes;
    std::vector<TriangleVerts> triangles;     // its meshes' triangles, in mesh order
    std::vector<std::uint32_t> triangleMesh;  // triangle -> mesh
    Bvh bvh;
    bool topologyDirty = false;  // meshes added since the last build
    bool moved = false;          // vertices updated since the last build or refit
  };

  std::vector<RtMesh> meshes_;
  std::vector<std::uint32_t> meshFirstTriangle_;  // into its group's triangles
  std::vector<Group> groups_{1};
  // Whether any group's BVH holds a triangle: group 0 is always there, empty in a
  // scene of spheres and planes, whose rays then skip the groups' boxes altogether.
  bool boxedTriangles_ = false;
  // See RootHits. Rays from beyond rootsOriginLimit_ (16 times the farthest box
  // coordinate) test the spheres regardless: the box's margin is sized for rays from
  // within it. Empty boxes until updateRoots.
  Bvh::Node roots_ = noRoots();
  float rootsOriginLimit_ = -1.0f;
  static Bvh::Node noRoots();
};

}  // namespace engine::rt
