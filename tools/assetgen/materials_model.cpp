#include "materials_model.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include <glm/gtc/constants.hpp>

#include "gltf_buffer.h"

namespace assetgen {

namespace {

using engine::Image;

// ---- textures ------------------------------------------------------------------

std::uint8_t toByte(float v) { return std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

// Fills an RGBA8 image from a function of the pixel centre (x, y in pixels, y
// down the image), averaged over 2 x 2 samples so painted edges are antialiased.
Image paint(int size, const std::function<glm::vec4(float, float)>& colour) {
  Image image(size, size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      glm::vec4 sum(0.0f);
      for (int sy = 0; sy < 2; ++sy)
        for (int sx = 0; sx < 2; ++sx) sum += colour(float(x) + 0.25f + 0.5f * float(sx), float(y) + 0.25f + 0.5f * float(sy));
      sum *= 0.25f;
      std::uint8_t* p = &image.pixels[(size_t(y) * size_t(size) + size_t(x)) * 4];
      for (int c = 0; c < 4; ++c) p[c] = toByte(sum[c]);
    }
  return image;
}

// A tangent-space normal map of a tileable height field (heights in pixels of
// the same image): central differences, wrapping at the borders. The map's +Y is
// up the image (glTF's OpenGL convention) while y runs down, hence the sign.
Image normalMap(int size, const std::function<float(float, float)>& height) {
  return paint(size, [&](float x, float y) {
    auto h = [&](float px, float py) {
      const float s = float(size);
      return height(std::fmod(px + s, s), std::fmod(py + s, s));
    };
    const float dx = 0.5f * (h(x + 1.0f, y) - h(x - 1.0f, y));
    const float dy = 0.5f * (h(x, y + 1.0f) - h(x, y - 1.0f));
    const glm::vec3 n = glm::normalize(glm::vec3(-dx, dy, 1.0f));
    return glm::vec4(n * 0.5f + 0.5f, 1.0f);
  });
}

// A small integer hash, for per-brick colour: the same on every platform.
float hash01(int a, int b) {
  std::uint32_t h = std::uint32_t(a) * 0x8da6b343u ^ std::uint32_t(b) * 0xd8163841u;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return float(h & 0xffffu) / 65535.0f;
}

// Running bond: 4 bricks of 64 x 32 pixels across a 256 pixel tile, every other
// row shifted by half a brick. Returns the distance to the nearest mortar line's
// centre and the brick's (column, row).
struct BrickCell {
  float edge;
  int column, row;
};

BrickCell brickCell(float x, float y) {
  const int row = int(std::floor(y / 32.0f));
  const float shifted = x + ((row & 1) ? 32.0f : 0.0f);
  const int column = int(std::floor(shifted / 64.0f));
  const float bx = shifted - 64.0f * float(column), by = y - 32.0f * float(row);
  return {std::min({bx, 64.0f - bx, by, 32.0f - by}), column & 3, row & 7};
}

constexpr float kMortar = 2.5f;  // half width of a mortar line, pixels
constexpr float kBevel = 4.0f;   // pixels over which a brick edge rounds off

float smoothstep(float a, float b, float x) {
  const float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

float brickHeight(float x, float y) { return kBevel * smoothstep(kMortar, kMortar + kBevel, brickCell(x, y).edge); }

Image bricksAlbedo() {
  return paint(256, [](float x, float y) {
    const BrickCell c = brickCell(x, y);
    const float shade = 0.8f + 0.35f * hash01(c.column, c.row);
    const glm::vec3 brick = glm::vec3(0.62f, 0.27f, 0.18f) * shade;
    const glm::vec3 mortar(0.72f, 0.70f, 0.66f);
    return glm::vec4(glm::mix(mortar, brick, smoothstep(kMortar - 0.5f, kMortar + 0.5f, c.edge)), 1.0f);
  });
}

// Occlusion darkens the mortar joints, roughness is high everywhere (mortar the
// most), nothing is metal.
Image bricksOrm() {
  return paint(256, [](float x, float y) {
    const float inside = smoothstep(kMortar, kMortar + kBevel, brickCell(x, y).edge);
    return glm::vec4(0.45f + 0.55f * inside, 1.0f - 0.2f * inside, 0.0f, 1.0f);
  });
}

// 4 x 4 square tiles of 32 pixels with narrow grout.
float tileEdge(float x, float y) {
  const float tx = std::fmod(x, 32.0f), ty = std::fmod(y, 32.0f);
  return std::min({tx, 32.0f - tx, ty, 32.0f - ty});
}

float tileHeight(float x, float y) { return 3.0f * smoothstep(1.5f, 4.5f, tileEdge(x, y)); }

// Checker of polished metal and rough dielectric tiles; the grout is rough.
Image tilesMetallicRoughness() {
  return paint(128, [](float x, float y) {
    const bool metal = ((int(x / 32.0f) + int(y / 32.0f)) & 1) == 0;
    const float tile = smoothstep(1.0f, 2.0f, tileEdge(x, y));
    const float roughness = glm::mix(1.0f, metal ? 0.25f : 0.7f, tile);
    const float metallic = metal ? tile : 0.0f;
    return glm::vec4(1.0f, roughness, metallic, 1.0f);
  });
}

// Glowing rings and a warm centre on black, for the emissive panel.
Image emissivePattern() {
  return paint(128, [](float x, float y) {
    const float r = glm::length(glm::vec2(x, y) - glm::vec2(64.0f));
    const float ring = std::max(0.0f, 1.0f - std::abs(std::fmod(r, 16.0f) - 8.0f) / 2.5f) * (r < 60.0f ? 1.0f : 0.0f);
    const float core = 1.0f - smoothstep(6.0f, 9.0f, r);
    const glm::vec3 c = glm::vec3(0.15f, 0.85f, 1.0f) * ring * (r > 10.0f ? 1.0f : 0.0f) + glm::vec3(1.0f, 0.55f, 0.12f) * core;
    return glm::vec4(c, 1.0f);
  });
}

// Leaves: ellipses with a midrib on a transparent background (alpha is the mask).
Image leaves() {
  struct Leaf {
    glm::vec2 center;
    float angle, length, width, shade;
  };
  const Leaf kLeaves[] = {{{30, 34}, 0.6f, 26, 10, 0.9f},   {{84, 26}, -0.4f, 28, 11, 1.0f},
                          {{60, 64}, 1.3f, 30, 12, 0.8f},   {{24, 92}, -0.9f, 24, 10, 1.05f},
                          {{98, 84}, 0.3f, 27, 11, 0.95f},  {{64, 108}, -1.4f, 22, 9, 0.85f},
                          {{108, 44}, 1.0f, 18, 8, 1.1f}};
  return paint(128, [&](float x, float y) {
    glm::vec4 out(0.0f);
    for (const Leaf& leaf : kLeaves) {
      const glm::vec2 d = glm::vec2(x, y) - leaf.center;
      const float c = std::cos(leaf.angle), s = std::sin(leaf.angle);
      const glm::vec2 local(c * d.x + s * d.y, -s * d.x + c * d.y);
      const float e = glm::length(local / glm::vec2(leaf.length, leaf.width));
      if (e > 1.0f) continue;
      const float rib = std::abs(local.y) < 0.8f ? 0.75f : 1.0f;
      out = glm::vec4(glm::vec3(0.22f, 0.48f, 0.14f) * leaf.shade * rib, 1.0f);
    }
    return out;
  });
}

// A glass pane: an opaque grey frame around a faintly streaked, mostly clear
// pane; the material's factor tints it.
Image glass() {
  return paint(128, [](float x, float y) {
    const float edge = std::min({x, 128.0f - x, y, 128.0f - y});
    if (edge < 7.0f) return glm::vec4(0.3f, 0.3f, 0.33f, 1.0f);
    const float streak = 0.08f * std::max(0.0f, std::sin((x + y) * 0.15f));
    return glm::vec4(1.0f, 1.0f, 1.0f, 0.3f + streak);
  });
}

// ---- meshes --------------------------------------------------------------------

struct Mesh {
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec2> uvs;
  std::vector<glm::vec4> tangents;  // empty: the loader generates them
  std::vector<std::uint16_t> indices;

  // A w x h rectangle in the plane through `origin` spanned by `right` and `up`
  // (unit), facing right x up; uv (0,0) at the top-left, `repeat` tiles across.
  void addQuad(glm::vec3 origin, glm::vec3 right, glm::vec3 up, float w, float h, glm::vec2 repeat, bool tangent) {
    const auto base = std::uint16_t(positions.size());
    const glm::vec3 n = glm::cross(right, up);
    const glm::vec2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};  // uv
    for (const glm::vec2& c : corners) {
      positions.push_back(origin + right * (c.x - 0.5f) * w + up * (0.5f - c.y) * h);
      normals.push_back(n);
      uvs.push_back(c * repeat);
      if (tangent) tangents.emplace_back(right, 1.0f);
    }
    for (int i : {0, 3, 1, 1, 3, 2}) indices.push_back(std::uint16_t(base + i));
  }
};

Mesh quad(float w, float h, glm::vec2 repeat = glm::vec2(1.0f), bool tangent = false) {
  Mesh m;
  m.addQuad(glm::vec3(0.0f, h * 0.5f, 0.0f), {1, 0, 0}, {0, 1, 0}, w, h, repeat, tangent);
  return m;
}

// A uv sphere, u around from +z, v from the north pole down, with its exact
// tangents (the validator warns about normal-mapped meshes without TANGENT).
Mesh sphere(float radius, int around, int down, glm::vec2 repeat) {
  Mesh m;
  for (int j = 0; j <= down; ++j) {
    const float v = float(j) / float(down), theta = v * glm::pi<float>();
    for (int i = 0; i <= around; ++i) {
      const float u = float(i) / float(around), phi = u * glm::two_pi<float>();
      const glm::vec3 n(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
      m.positions.push_back(n * radius);
      m.normals.push_back(n);
      m.uvs.push_back(glm::vec2(u, v) * repeat);
      // u grows eastward: the tangent is d(position)/d(phi), defined at the poles
      // too; v grows southward, so up the image is north and w = +1.
      m.tangents.emplace_back(std::cos(phi), 0.0f, -std::sin(phi), 1.0f);
    }
  }
  const int row = around + 1;
  for (int j = 0; j < down; ++j)
    for (int i = 0; i < around; ++i) {
      const int a = j * row + i, b = a + row;
      for (int k : {a, b, a + 1, a + 1, b, b + 1}) m.indices.push_back(std::uint16_t(k));
    }
  return m;
}

// Two cards crossed at right angles: a bush from any side.
Mesh crossedCards(float w, float h) {
  Mesh m;
  m.addQuad({0, h * 0.5f, 0}, {1, 0, 0}, {0, 1, 0}, w, h, glm::vec2(1.0f), false);
  m.addQuad({0, h * 0.5f, 0}, {0, 0, -1}, {0, 1, 0}, w, h, glm::vec2(1.0f), false);
  return m;
}

std::vector<float> flatten(const std::vector<glm::vec2>& v) {
  std::vector<float> out;
  for (const glm::vec2& e : v) out.insert(out.end(), {e.x, e.y});
  return out;
}
std::vector<float> flatten(const std::vector<glm::vec3>& v) {
  std::vector<float> out;
  for (const glm::vec3& e : v) out.insert(out.end(), {e.x, e.y, e.z});
  return out;
}
std::vector<float> flatten(const std::vector<glm::vec4>& v) {
  std::vector<float> out;
  for (const glm::vec4& e : v) out.insert(out.end(), {e.x, e.y, e.z, e.w});
  return out;
}

Json primitive(const Mesh& mesh, int material, BufferBuilder& buffer) {
  Json attributes;
  attributes["POSITION"] = buffer.addFloats(flatten(mesh.positions), 3, "VEC3", true);
  attributes["NORMAL"] = buffer.addFloats(flatten(mesh.normals), 3, "VEC3", false);
  attributes["TEXCOORD_0"] = buffer.addFloats(flatten(mesh.uvs), 2, "VEC2", false);
  if (!mesh.tangents.empty()) attributes["TANGENT"] = buffer.addFloats(flatten(mesh.tangents), 4, "VEC4", false);
  std::vector<std::uint8_t> bytes(mesh.indices.size() * 2);
  std::memcpy(bytes.data(), mesh.indices.data(), bytes.size());
  const int view = buffer.addView(bytes, kElementArrayBuffer, 0);
  const int indices = buffer.addAccessor(view, 0, kUnsignedShort, mesh.indices.size(), "SCALAR");
  return {{"attributes", attributes}, {"indices", indices}, {"material", material}, {"mode", 4}};
}

Json textureRef(int texture) { return {{"index", texture}}; }

// A quarter turn and a half turn about +y, as glTF quaternions (x, y, z, w).
Json yRotation(float degrees) {
  const float half = glm::radians(degrees) * 0.5f;
  return Json::array({0.0f, std::sin(half), 0.0f, std::cos(half)});
}

}  // namespace

MaterialsModel buildMaterialsModel(const std::string& baseName) {
  MaterialsModel model;
  const char* kImages[] = {"bricks_albedo", "bricks_normal", "bricks_orm", "tiles_normal",
                           "tiles_mr",      "emissive",      "leaves",     "glass"};
  model.images = {{"", bricksAlbedo()},
                  {"", normalMap(256, brickHeight)},
                  {"", bricksOrm()},
                  {"", normalMap(128, tileHeight)},
                  {"", tilesMetallicRoughness()},
                  {"", emissivePattern()},
                  {"", leaves()},
                  {"", glass()}};
  enum Texture { kBricksAlbedo, kBricksNormal, kBricksOrm, kTilesNormal, kTilesMr, kEmissive, kLeaves, kGlass };

  Json doc;
  doc["asset"] = {{"version", "2.0"}, {"generator", "demo_engine tools/assetgen"}};
  doc["scene"] = 0;
  for (const char* key : {"scenes", "nodes", "meshes", "materials", "textures", "samplers", "images", "accessors",
                          "bufferViews", "buffers"})
    doc[key] = Json::array();
  // Textures tile (repeat); the glass and leaf cards do not.
  doc["samplers"].push_back({{"magFilter", kLinear}, {"minFilter", kLinearMipmapLinear}, {"wrapS", kRepeat}, {"wrapT", kRepeat}});
  doc["samplers"].push_back(
      {{"magFilter", kLinear}, {"minFilter", kLinearMipmapLinear}, {"wrapS", kClampToEdge}, {"wrapT", kClampToEdge}});
  for (size_t i = 0; i < model.images.size(); ++i) {
    model.images[i].first = baseName + "_" + kImages[i] + ".png";
    doc["images"].push_back({{"name", kImages[i]}, {"uri", model.images[i].first}});
    const bool clamp = i == kLeaves || i == kGlass;
    doc["textures"].push_back({{"sampler", clamp ? 1 : 0}, {"source", i}});
  }

  auto pbr = [](Json base, float metallic, float roughness) {
    base["metallicFactor"] = metallic;
    base["roughnessFactor"] = roughness;
    return base;
  };
  Json& materials = doc["materials"];
  materials.push_back({{"name", "bricks"},
                       {"pbrMetallicRoughness", pbr({{"baseColorTexture", textureRef(kBricksAlbedo)},
                                                     {"metallicRoughnessTexture", textureRef(kBricksOrm)}},
                                                    1.0f, 1.0f)},
                       {"normalTexture", textureRef(kBricksNormal)},
                       {"occlusionTexture", {{"index", kBricksOrm}, {"strength", 1.0f}}}});
  materials.push_back({{"name", "tiles"},
                       {"pbrMetallicRoughness", pbr({{"baseColorFactor", {0.85f, 0.78f, 0.62f, 1.0f}},
                                                     {"metallicRoughnessTexture", textureRef(kTilesMr)}},
                                                    1.0f, 1.0f)},
                       {"normalTexture", {{"index", kTilesNormal}, {"scale", 1.0f}}}});
  materials.push_back({{"name", "emissive_panel"},
                       {"pbrMetallicRoughness", pbr({{"baseColorFactor", {0.04f, 0.04f, 0.05f, 1.0f}}}, 0.0f, 0.4f)},
                       {"emissiveTexture", textureRef(kEmissive)},
                       {"emissiveFactor", {1.0f, 1.0f, 1.0f}}});
  materials.push_back({{"name", "leaves"},
                       {"pbrMetallicRoughness", pbr({{"baseColorTexture", textureRef(kLeaves)}}, 0.0f, 0.8f)},
                       {"alphaMode", "MASK"},
                       {"alphaCutoff", 0.5f},
                       {"doubleSided", true}});
  materials.push_back({{"name", "glass_blue"},
                       {"pbrMetallicRoughness", pbr({{"baseColorFactor", {0.45f, 0.75f, 1.0f, 1.0f}},
                                                     {"baseColorTexture", textureRef(kGlass)}},
                                                    0.0f, 0.1f)},
                       {"alphaMode", "BLEND"}});
  materials.push_back({{"name", "glass_amber"},
                       {"pbrMetallicRoughness", pbr({{"baseColorFactor", {1.0f, 0.65f, 0.25f, 1.0f}},
                                                     {"baseColorTexture", textureRef(kGlass)}},
                                                    0.0f, 0.1f)},
                       {"alphaMode", "BLEND"}});
  materials.push_back({{"name", "two_sided"},
                       {"pbrMetallicRoughness", pbr({{"baseColorFactor", {0.6f, 0.22f, 0.04f, 1.0f}}}, 0.0f, 0.6f)},
                       {"doubleSided", true}});
  materials.push_back({{"name", "one_sided"},
                       {"pbrMetallicRoughness", pbr({{"baseColorFactor", {0.1f, 0.3f, 0.9f, 1.0f}}}, 0.0f, 0.6f)}});

  BufferBuilder buffer(doc);
  struct Part {
    const char* name;
    Mesh mesh;
    int material;
    glm::vec3 translation;
    float yawDegrees;
  };
  // Laid out for assets/scenes/materials.json: the camera looks along -z at the
  // origin; the sun comes from the front left, grazing the wall so its bricks show.
  const Part parts[] = {
      {"brick_wall", quad(3.0f, 2.0f, {3.0f, 2.0f}, true), 0, {-1.6f, 0.0f, -2.0f}, 0.0f},
      {"tiled_sphere", sphere(0.6f, 48, 24, {4.0f, 2.0f}), 1, {0.7f, 0.6f, -1.4f}, 0.0f},
      {"emissive_panel", quad(1.0f, 1.0f), 2, {2.4f, 0.3f, -2.0f}, -20.0f},
      {"bush", crossedCards(1.2f, 1.2f), 3, {-2.3f, 0.0f, 0.2f}, 30.0f},
      {"glass_back", quad(1.0f, 1.2f), 4, {-0.9f, 0.1f, 0.0f}, 10.0f},
      {"glass_front", quad(1.0f, 1.2f), 5, {-0.35f, 0.15f, 1.0f}, -10.0f},
      {"two_sided_quad", quad(0.8f, 0.8f), 6, {1.6f, 0.0f, 0.9f}, 160.0f},
      {"one_sided_quad", quad(0.8f, 0.8f), 7, {2.6f, 0.0f, 0.9f}, 160.0f},
  };
  Json roots = Json::array();
  for (const Part& part : parts) {
    const size_t index = doc["nodes"].size();
    doc["meshes"].push_back({{"name", part.name}, {"primitives", Json::array({primitive(part.mesh, part.material, buffer)})}});
    Json node = {{"name", part.name}, {"mesh", index}, {"translation", vec3Json(part.translation)}};
    if (part.yawDegrees != 0.0f) node["rotation"] = yRotation(part.yawDegrees);
    doc["nodes"].push_back(node);
    roots.push_back(index);
  }
  doc["scenes"].push_back({{"name", "materials"}, {"nodes", roots}});
  model.bin = buffer.take();
  doc["buffers"].push_back({{"uri", baseName + ".bin"}, {"byteLength", model.bin.size()}});
  model.json = doc.dump(1) + "\n";
  return model;
}

}  // namespace assetgen
