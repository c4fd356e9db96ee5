#include "terrain/terrain_renderer.h"

#include <algorithm>
#include <cmath>

#include "terrain/materials.h"

namespace engine::terrain {
namespace {

constexpr int kLayerImageSize = 256;
constexpr GLsizei kIndexCount = kPatchQuads * kPatchQuads * 6;
constexpr int kMaxPatchesPerDraw = 4 * kGpuPageSlots;

struct Instance {
  GLint gx, gz, level, slot;
};

std::vector<std::uint16_t> gridVertices() {
  std::vector<std::uint16_t> v;
  for (int j = 0; j <= kPatchQuads; ++j)
    for (int i = 0; i <= kPatchQuads; ++i) {
      v.push_back(std::uint16_t(i));
      v.push_back(std::uint16_t(j));
    }
  return v;
}

// Every quad split along its (i, j)-(i+1, j+1) diagonal, the direction the morph
// and the error estimate assume; counter-clockwise seen from above.
std::vector<std::uint16_t> gridIndices() {
  std::vector<std::uint16_t> idx;
  auto at = [](int i, int j) { return std::uint16_t(j * (kPatchQuads + 1) + i); };
  for (int j = 0; j < kPatchQuads; ++j)
    for (int i = 0; i < kPatchQuads; ++i) {
      idx.insert(idx.end(), {at(i, j), at(i + 1, j + 1), at(i + 1, j)});
      idx.insert(idx.end(), {at(i, j), at(i, j + 1), at(i + 1, j + 1)});
    }
  return idx;
}

gl::Texture uploadLayer(const Image& image) {
  gl::Texture t = gl::Texture::create2D(GL_SRGB8_ALPHA8, image.width, image.height, 0);
  t.uploadRgba8(image.pixels.data());
  t.generateMipmaps();
  t.parameter(GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  t.parameter(GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  t.parameter(GL_TEXTURE_WRAP_S, GL_REPEAT);
  t.parameter(GL_TEXTURE_WRAP_T, GL_REPEAT);
  return t;
}

}  // namespace

Result<TerrainRenderer> TerrainRenderer::create(const std::string& shaderDir, const Terrain& terrain,
                                                const std::vector<std::string>& defines) {
  auto program = gl::Program::build(
      shaderDir, {{GL_VERTEX_SHADER, "terrain.vert"}, {GL_FRAGMENT_SHADER, "terrain.frag"}}, defines);
  if (!program) return program.error();
  TerrainRenderer r;
  r.terrain_ = &terrain;
  r.program_ = std::move(program).value();

  const auto vertices = gridVertices();
  const auto indices = gridIndices();
  r.vertices_ = gl::Buffer::fromSpan(std::span<const std::uint16_t>(vertices), 0);
  r.indices_ = gl::Buffer::fromSpan(std::span<const std::uint16_t>(indices), 0);
  r.instances_ = gl::Buffer::create(sizeof(Instance) * kMaxPatchesPerDraw);
  r.vertexArray_ = gl::VertexArray::create();
  r.vertexArray_.integerAttribute(0, 0, 2, 0, GL_UNSIGNED_SHORT);
  r.vertexArray_.vertexBuffer(0, r.vertices_, 2 * sizeof(std::uint16_t));
  r.vertexArray_.integerAttribute(1, 1, 4, 0, GL_INT);
  r.vertexArray_.vertexBuffer(1, r.instances_, sizeof(Instance));
  glVertexArrayBindingDivisor(r.vertexArray_.id(), 1, 1);
  r.vertexArray_.indexBuffer(r.indices_);

  GLint maxLayers = 0;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  r.slots_ = std::min(kGpuPageSlots, int(maxLayers));
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &id);
  r.heightPages_ = gl::Object<gl::TextureDeleter>(id);
  glTextureStorage3D(id, 1, GL_R32F, kPageSide, kPageSide, r.slots_);
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  r.slotKey_.assign(std::size_t(r.slots_), PageKey{-1, 0, 0});
  r.slotUsed_.assign(std::size_t(r.slots_), 0);

  for (TerrainLayer layer : kTerrainLayers) r.layers_.push_back(uploadLayer(makeLayerImage(layer, kLayerImageSize)));
  return r;
}

// The slot holding `key`, uploading it into a free or least recently used slot;
// -1 when every slot already serves this frame.
int TerrainRenderer::residentSlot(const PageKey& key, std::size_t& uploads) {
  if (auto it = slotOf_.find(key); it != slotOf_.end()) {
    slotUsed_[std::size_t(it->second)] = frame_;
    return it->second;
  }
  const auto oldest = std::min_element(slotUsed_.begin(), slotUsed_.end());
  if (*oldest == frame_) return -1;
  const int slot = int(oldest - slotUsed_.begin());
  if (slotKey_[std::size_t(slot)].level >= 0) slotOf_.erase(slotKey_[std::size_t(slot)]);
  auto page = terrain_->page(key);
  glTextureSubImage3D(heightPages_.id(), 0, 0, 0, slot, kPageSide, kPageSide, 1, GL_RED, GL_FLOAT,
                      page->heights.data());
  slotKey_[std::size_t(slot)] = key;
  slotUsed_[std::size_t(slot)] = frame_;
  slotOf_[key] = slot;
  ++uploads;
  return slot;
}

TerrainDrawStats TerrainRenderer::draw(const LodSelection& selection, const glm::mat4& viewProjection,
                                       const glm::dvec3& cameraPosition, const UniformSetter& setUniforms) {
  TerrainDrawStats stats;
  ++frame_;
  std::vector<Instance> instances;
  instances.reserve(selection.patches.size());
  for (const LodPatch& p : selection.patches) {
    const int slot = instances.size() < std::size_t(kMaxPatchesPerDraw) ? residentSlot(p.node, stats.pagesUploaded) : -1;
    if (slot < 0) {
      ++stats.patchesSkipped;
      continue;
    }
    instances.push_back({p.gx, p.gz, p.level, slot});
    stats.maxGeometricError = std::max(stats.maxGeometricError, p.error);
  }
  stats.patchesDrawn = instances.size();
  stats.trianglesDrawn = instances.size() * kPatchQuads * kPatchQuads * 2;
  if (instances.empty()) return stats;
  instances_.upload(0, instances.size() * sizeof(Instance), instances.data());

  const gl::Program& p = program_;
  p.set("u_viewProjection", viewProjection);
  glProgramUniform2i(p.id(), p.location("u_cameraCell"), selection.cameraCell.x, selection.cameraCell.y);
  glProgramUniform2f(p.id(), p.location("u_cameraFraction"), selection.cameraFraction.x,
                     selection.cameraFraction.y);
  glProgramUniform2i(p.id(), p.location("u_cells"), selection.cells.x, selection.cells.y);
  p.set("u_cameraHeight", selection.cameraHeight);
  p.set("u_morphDy2", selection.morphDy2);
  p.set("u_spacing", selection.spacing);
  glProgramUniform1fv(p.id(), p.location("u_morphStart"), kMaxLevels, selection.morphStart.data());
  glProgramUniform1fv(p.id(), p.location("u_morphEnd"), kMaxLevels, selection.morphEnd.data());
  p.set("u_heightScale", std::max(terrain_->heightRange().max, 1e-3f));
  // Texture coordinates are camera-relative too: the camera's offset from the
  // origin in tiles, reduced to [0, 1) in double, keeps them small and exact.
  const glm::dvec3 fromOrigin = cameraPosition - terrain_->origin();
  const glm::dvec2 tiles = glm::dvec2(fromOrigin.x, fromOrigin.z) / double(kLayerTileMetres);
  const glm::vec2 uvOffset(tiles - glm::floor(tiles));
  glProgramUniform2f(p.id(), p.location("u_uvOffset"), uvOffset.x, uvOffset.y);
  p.set("u_tileMetres", kLayerTileMetres);
  if (setUniforms) setUniforms(p);

  p.use();
  glBindTextureUnit(0, heightPages_.id());
  for (std::size_t i = 0; i < layers_.size(); ++i) layers_[i].bind(GLuint(1 + i));
  vertexArray_.bind();
  glDrawElementsInstanced(GL_TRIANGLES, kIndexCount, GL_UNSIGNED_SHORT, nullptr, GLsizei(instances.size()));
  glBindVertexArray(0);
  return stats;
}

}  // namespace engine::terrain
