#include "terrain/terrain_renderer.h"

#include <algorithm>
#include <cmath>

#include "gl/bindings.h"
#include "terrain/materials.h"

namespace engine::terrain {
namespace {

constexpr GLsizei kIndexCount = kPatchQuads * kPatchQuads * 6;
constexpr std::size_t kInitialInstances = 1024;

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

// patchIndices() in 16 bits: a patch has 33^2 vertices.
std::vector<std::uint16_t> gridIndices() {
  const std::vector<std::uint32_t> wide = patchIndices();
  return std::vector<std::uint16_t>(wide.begin(), wide.end());
}

}  // namespace

Result<TerrainRenderer> TerrainRenderer::create(const std::string& shaderDir, const Terrain& terrain,
                                                const std::vector<std::string>& defines,
                                                std::size_t gpuBudgetBytes) {
  auto program = gl::Program::build(
      shaderDir, {{GL_VERTEX_SHADER, "terrain.vert"}, {GL_FRAGMENT_SHADER, "terrain.frag"}}, defines);
  if (!program) return program.error();
  auto depthProgram = gl::Program::build(
      shaderDir, {{GL_VERTEX_SHADER, "terrain.vert"}, {GL_FRAGMENT_SHADER, "depth.frag"}}, {"DEPTH_ONLY 1"});
  if (!depthProgram) return depthProgram.error();
  TerrainRenderer r;
  r.terrain_ = &terrain;
  r.program_ = std::move(program).value();
  r.depthProgram_ = std::move(depthProgram).value();

  const auto vertices = gridVertices();
  const auto indices = gridIndices();
  r.vertices_ = gl::Buffer::fromSpan(std::span<const std::uint16_t>(vertices), 0);
  r.indices_ = gl::Buffer::fromSpan(std::span<const std::uint16_t>(indices), 0);
  r.instances_ = gl::Buffer::create(sizeof(Instance) * kInitialInstances);
  r.vertexArray_ = gl::VertexArray::create();
  r.vertexArray_.integerAttribute(0, 0, 2, 0, GL_UNSIGNED_SHORT);
  r.vertexArray_.vertexBuffer(0, r.vertices_, 2 * sizeof(std::uint16_t));
  r.vertexArray_.integerAttribute(1, 1, 4, 0, GL_INT);
  r.vertexArray_.vertexBuffer(1, r.instances_, sizeof(Instance));
  glVertexArrayBindingDivisor(r.vertexArray_.id(), 1, 1);
  r.vertexArray_.indexBuffer(r.indices_);

  // Slots from the budget, rounded down to whole atlas layers.
  GLint maxLayers = 0;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  r.atlasLayers_ = pageLayersWithin(gpuBudgetBytes, maxLayers);
  r.slots_ = r.atlasLayers_ * kPagesPerLayer;
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &id);
  r.heightPages_ = gl::Object<gl::TextureDeleter>(id);
  glTextureStorage3D(id, 1, GL_R32F, kPageSide * kPageAtlas, kPageSide * kPageAtlas, r.atlasLayers_);
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  r.slotKey_.assign(std::size_t(r.slots_), PageKey{-1, 0, 0});
  r.slotUsed_.assign(std::size_t(r.slots_), 0);

  for (TerrainLayer layer : kTerrainLayers) {
    const Image image = makeLayerImage(layer, kLayerImageSize);
    r.layers_.push_back(gl::Texture::fromImage(image, true));
    r.layerBytes_ += image.pixels.size() * 4 / 3;  // with its mip chain
  }
  return r;
}

std::size_t TerrainRenderer::gpuBytes() const {
  return std::size_t(slots_) * kGpuPageBytes + instances_.size() + vertices_.size() + indices_.size() +
         layerBytes_;
}

// Puts the `missing` pages into the slots not used by this draw, least recently
// used first. The caller has checked that there are enough such slots.
void TerrainRenderer::assignSlots(const std::vector<PageKey>& missing, std::size_t& uploads) {
  if (missing.empty()) return;
  std::vector<int> candidates;
  candidates.reserve(slotUsed_.size());
  for (int i = 0; i < slots_; ++i)
    if (slotUsed_[std::size_t(i)] != frame_) candidates.push_back(i);
  const auto oldestFirst = [this](int a, int b) { return slotUsed_[std::size_t(a)] < slotUsed_[std::size_t(b)]; };
  const auto end = candidates.begin() + std::ptrdiff_t(missing.size());
  std::nth_element(candidates.begin(), end - 1, candidates.end(), oldestFirst);
  for (std::size_t i = 0; i < missing.size(); ++i) {
    const int slot = candidates[i];
    const std::size_t si = std::size_t(slot);
    if (slotKey_[si].level >= 0) slotOf_.erase(slotKey_[si]);
    const auto page = terrain_->page(missing[i]);
    const int tile = slot % kPagesPerLayer;
    glTextureSubImage3D(heightPages_.id(), 0, (tile % kPageAtlas) * kPageSide, (tile / kPageAtlas) * kPageSide,
                        slot / kPagesPerLayer, kPageSide, kPageSide, 1, GL_RED, GL_FLOAT, page->heights.data());
    slotKey_[si] = missing[i];
    slotUsed_[si] = frame_;
    slotOf_[missing[i]] = slot;
    ++uploads;
  }
}

// Makes the selection's pages resident and fills the instance buffer.
TerrainDrawStats TerrainRenderer::upload(const LodSelection& selection) {
  TerrainDrawStats stats;
  ++frame_;
  // Pass 1: mark what is resident, list what is not (once per page).
  std::vector<PageKey> missing;
  std::unordered_map<PageKey, int, PageKeyHash> pending;
  for (const LodPatch& p : selection.patches) {
    if (auto it = slotOf_.find(p.node); it != slotOf_.end()) {
      slotUsed_[std::size_t(it->second)] = frame_;
    } else if (pending.emplace(p.node, 0).second) {
      missing.push_back(p.node);
    }
  }
  std::size_t inUse = 0;
  for (std::uint64_t used : slotUsed_) inUse += used == frame_;
  // Over budget (only for a selection not made with selectLodWithin): the pages
  // that do not fit are left out, and so are their patches, counted.
  const std::size_t fits = std::min(missing.size(), std::size_t(slots_) - inUse);
  missing.resize(fits);
  assignSlots(missing, stats.pagesUploaded);

  std::vector<Instance> instances;
  instances.reserve(selection.patches.size());
  drawnPatches_.clear();
  for (const LodPatch& p : selection.patches) {
    const auto it = slotOf_.find(p.node);
    if (it == slotOf_.end() || slotUsed_[std::size_t(it->second)] != frame_) {
      ++stats.patchesSkipped;
      continue;
    }
    instances.push_back({p.gx, p.gz, p.level, it->second});
    drawnPatches_.push_back(p);
    stats.maxGeometricError = std::max(stats.maxGeometricError, p.error);
  }
  stats.patchesDrawn = instances.size();
  stats.trianglesDrawn = instances.size() * kPatchQuads * kPatchQuads * 2;
  const std::size_t bytes = instances.size() * sizeof(Instance);
  if (bytes > instances_.size()) {
    instances_ = gl::Buffer::create(std::max(bytes, 2 * instances_.size()));
    vertexArray_.vertexBuffer(1, instances_, sizeof(Instance));
  }
  if (bytes > 0) instances_.upload(0, bytes, instances.data());
  return stats;
}

void TerrainRenderer::setGridUniforms(const gl::Program& p, const LodSelection& selection) const {
  glProgramUniform2i(p.id(), p.location("u_cameraCell"), selection.cameraCell.x, selection.cameraCell.y);
  glProgramUniform2f(p.id(), p.location("u_cameraFraction"), selection.cameraFraction.x,
                     selection.cameraFraction.y);
  glProgramUniform2i(p.id(), p.location("u_cells"), selection.cells.x, selection.cells.y);
  p.set("u_cameraHeight", selection.cameraHeight);
  p.set("u_morphDy2", selection.morphDy2);
  p.set("u_spacing", selection.spacing);
  glProgramUniform1fv(p.id(), p.location("u_morphStart"), kMaxLevels, selection.morphStart.data());
  glProgramUniform1fv(p.id(), p.location("u_morphEnd"), kMaxLevels, selection.morphEnd.data());
}

void TerrainRenderer::drawInstances(std::size_t count) const {
  glBindTextureUnit(gl::binding::kTerrainHeights, heightPages_.id());
  vertexArray_.bind();
  glDrawElementsInstanced(GL_TRIANGLES, kIndexCount, GL_UNSIGNED_SHORT, nullptr, GLsizei(count));
  glBindVertexArray(0);
}

int TerrainRenderer::indexCount() { return kIndexCount; }

void TerrainRenderer::useShadingProgram(const gl::Program& p, const LodSelection& selection,
                                        const glm::dvec3& cameraPosition, const UniformSetter& setUniforms) const {
  p.set("u_cameraHeight", selection.cameraHeight);
  p.set("u_heightScale", std::max(terrain_->heightRange().max, 1e-3f));
  // Texture coordinates are camera-relative too.
  const glm::vec2 uvOffset = layerUvOffset(cameraPosition - terrain_->origin());
  glProgramUniform2f(p.id(), p.location("u_uvOffset"), uvOffset.x, uvOffset.y);
  p.set("u_tileMetres", kLayerTileMetres);
  p.use();
  if (setUniforms) setUniforms(p);
  for (std::size_t i = 0; i < layers_.size(); ++i) layers_[i].bind(GLuint(gl::binding::kTerrainLayers + i));
}

TerrainDrawStats TerrainRenderer::draw(const LodSelection& selection, const glm::dvec3& cameraPosition,
                                       const UniformSetter& setUniforms, TerrainOutput output) {
  const TerrainDrawStats stats = upload(selection);
  if (stats.patchesDrawn == 0) return stats;
  useColourProgram(selection, cameraPosition, setUniforms, output);
  drawInstances(stats.patchesDrawn);
  return stats;
}

void TerrainRenderer::drawIndirect(const LodSelection& selection, const glm::dvec3& cameraPosition,
                                   const UniformSetter& setUniforms, std::intptr_t offset, int count,
                                   TerrainOutput output) const {
  if (count <= 0) return;
  useColourProgram(selection, cameraPosition, setUniforms, output);
  glBindTextureUnit(gl::binding::kTerrainHeights, heightPages_.id());
  vertexArray_.bind();
  glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_SHORT, reinterpret_cast<const void*>(offset), count, 0);
  glBindVertexArray(0);
}

Status TerrainRenderer::enableDeferred(const std::string& shaderDir, const std::vector<std::string>& defines) {
  std::vector<std::string> surfaceDefines = defines;
  surfaceDefines.push_back("TERRAIN_SURFACE 1");
  auto surface = gl::Program::build(
      shaderDir, {{GL_VERTEX_SHADER, "terrain.vert"}, {GL_FRAGMENT_SHADER, "terrain.frag"}}, surfaceDefines);
  if (!surface) return surface.error();
  auto deferred = gl::Program::build(
      shaderDir, {{GL_VERTEX_SHADER, "sky.vert"}, {GL_FRAGMENT_SHADER, "terrain_deferred.frag"}}, defines);
  if (!deferred) return deferred.error();
  surfaceProgram_ = std::move(surface).value();
  deferredProgram_ = std::move(deferred).value();
  emptyVertexArray_ = gl::VertexArray::create();
  return Ok{};
}

void TerrainRenderer::shadeDeferred(const LodSelection& selection, const glm::dvec3& cameraPosition,
                                    const glm::mat4& inverseViewProjection, const UniformSetter& setUniforms) const {
  useShadingProgram(deferredProgram_, selection, cameraPosition, setUniforms);
  deferredProgram_.set("u_inverseViewProjection", inverseViewProjection);
  emptyVertexArray_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
}

TerrainDrawStats TerrainRenderer::drawDepth(const LodSelection& selection, const glm::mat4& lightViewProjection) {
  const TerrainDrawStats stats = upload(selection);
  if (stats.patchesDrawn == 0) return stats;
  setGridUniforms(depthProgram_, selection);
  depthProgram_.set("u_lightViewProjection", lightViewProjection);
  depthProgram_.use();
  drawInstances(stats.patchesDrawn);
  return stats;
}

}  // namespace engine::terrain
