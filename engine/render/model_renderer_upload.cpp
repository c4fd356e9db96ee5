// A model's upload: each primitive's buffers (in runs, with its levels and
// clusters, where it is an indexed triangle list), its vertex array, and the
// images, samplers and tables its materials use.
#include <algorithm>
#include <cstdint>
#include <span>

#include "asset/vertex_cache.h"
#include "core/sheen_table.h"
#include "render/model_renderer.h"

namespace engine {
namespace {

template <typename T>
int addBuffer(GpuPrimitive& prim, const std::vector<T>& data) {
  prim.buffers.push_back(gl::Buffer::fromSpan(std::span<const T>(data)));
  return int(prim.buffers.size()) - 1;
}

// Appends a target-major attribute (PrimitiveData) vertex-major, so that the shader
// reads one vertex's displacements together, each padded to a vec4 (one load each in
// the shader, not three: llvmpipe checks every storage-buffer load); returns where
// the block starts (in vec4s), or -1 when no target moves the attribute.
int appendVertexMajor(std::vector<glm::vec4>& out, const std::vector<glm::vec3>& deltas, size_t vertices,
                      size_t targets) {
  if (deltas.empty()) return -1;
  const int start = int(out.size());
  for (size_t v = 0; v < vertices; ++v)
    for (size_t t = 0; t < targets; ++t) out.emplace_back(deltas[t * vertices + v], 0.0f);
  return start;
}

void uploadMorphTargets(const PrimitiveData& data, GpuPrimitive& prim) {
  if (data.morphTargets == 0) return;
  const size_t vertices = data.positions.size(), targets = size_t(data.morphTargets);
  std::vector<glm::vec4> deltas;
  prim.morphTargets = data.morphTargets;
  prim.morphPositions = appendVertexMajor(deltas, data.morphPositions, vertices, targets);
  prim.morphNormals = appendVertexMajor(deltas, data.morphNormals, vertices, targets);
  prim.morphTangents = appendVertexMajor(deltas, data.morphTangents, vertices, targets);
  // A buffer of at least one element: targets that move nothing still bind one.
  if (deltas.empty()) deltas.emplace_back(0.0f);
  prim.morphDeltas = gl::Buffer::fromSpan(std::span<const glm::vec4>(deltas));
  prim.morphDeltaTexture = gl::Texture::ofBuffer(prim.morphDeltas, GL_RGBA32F);
}

// The triangles of `indices` in vertex cache order when `reorder` (asset/vertex_cache.h).
std::vector<std::uint32_t> orderedIndices(const std::vector<std::uint32_t>& indices, std::size_t vertices, bool reorder) {
  return reorder ? orderForVertexCache(indices, vertices) : indices;
}

// Target-major displacements (PrimitiveData's morph arrays) in `split`'s vertex order.
std::vector<glm::vec3> targetsInSplitOrder(const std::vector<glm::vec3>& deltas, const RunSplit& split,
                                           std::size_t vertices, std::size_t targets) {
  std::vector<glm::vec3> out;
  if (deltas.empty()) return out;
  out.reserve(split.sourceVertex.size() * targets);
  for (std::size_t t = 0; t < targets; ++t)
    for (const std::uint32_t v : split.sourceVertex) out.push_back(deltas[t * vertices + v]);
  return out;
}

// `data`'s vertices (every attribute and morph displacement) as `split` copies them;
// its indices are left for the caller to set.
PrimitiveData verticesInSplitOrder(const PrimitiveData& data, const RunSplit& split) {
  PrimitiveData out = data;
  const std::size_t vertices = data.positions.size(), targets = std::size_t(data.morphTargets);
  const std::size_t influences = std::size_t(std::max(data.influences, 1));
  out.positions = inSplitOrder(data.positions, split);
  out.normals = inSplitOrder(data.normals, split);
  out.uvs = inSplitOrder(data.uvs, split);
  out.uvs1 = inSplitOrder(data.uvs1, split);
  out.colors = inSplitOrder(data.colors, split);
  out.tangents = inSplitOrder(data.tangents, split);
  out.joints = inSplitOrder(data.joints, split, influences);
  out.weights = inSplitOrder(data.weights, split, influences);
  out.morphPositions = targetsInSplitOrder(data.morphPositions, split, vertices, targets);
  out.morphNormals = targetsInSplitOrder(data.morphNormals, split, vertices, targets);
  out.morphTangents = targetsInSplitOrder(data.morphTangents, split, vertices, targets);
  return out;
}

// The full mesh's indices, then each level's, as the 32-bit index buffer holds them:
// into the split's vertices, the full mesh's through its runs, a level's through
// the first copy of each vertex (levels are drawn whole, not in runs).
std::vector<std::uint32_t> splitIndicesWithLevels(const RunSplit& split, const std::vector<std::vector<std::uint32_t>>& levels,
                                                  GpuPrimitive& prim) {
  std::vector<std::uint32_t> indices = indicesIntoCopies(split);
  for (std::size_t l = 0; l < levels.size(); ++l) {
    prim.levels[l].firstIndex = GLsizei(indices.size());
    for (const std::uint32_t v : levels[l]) indices.push_back(split.firstCopy[v]);
  }
  return indices;
}

// GPU culling's clusters (render/cull_math.h): the full mesh's indices, then each
// level's, as they lie in the one index buffer. Bounded by the rest positions:
// a deforming mesh is culled by its instance's bounds alone.
void addClusters(const PrimitiveData& data, const std::vector<std::uint32_t>& indices, GpuPrimitive& prim) {
  prim.fullClusters = cull::appendClusters(data.positions, indices, 0, std::uint32_t(prim.indexCount), prim.clusters);
  for (GpuPrimitive::Level& level : prim.levels) {
    level.clusters = cull::appendClusters(data.positions, indices, std::uint32_t(level.firstIndex),
                                          std::uint32_t(level.indexCount), prim.clusters);
  }
}

// `prim`'s buffers of `data`'s vertex attributes, where the vertex array reads them.
void addVertexBuffers(const PrimitiveData& data, GpuPrimitive& prim) {
  // One buffer per attribute: glTF keeps them apart and the shaders need only
  // some of them.
  GpuPrimitive::Sources& in = prim.sources;
  in.positions = addBuffer(prim, data.positions);
  if (!data.normals.empty()) in.normals = addBuffer(prim, data.normals);
  if (!data.uvs.empty()) in.uvs = addBuffer(prim, data.uvs);
  if (!data.uvs1.empty()) in.uvs1 = addBuffer(prim, data.uvs1);
  if (!data.colors.empty()) in.colors = addBuffer(prim, data.colors);
  if (data.influences > 0) {
    in.joints = addBuffer(prim, data.joints);
    in.weights = addBuffer(prim, data.weights);
  }
  if (!data.tangents.empty()) in.tangents = addBuffer(prim, data.tangents);
  prim.hasTangents = in.tangents >= 0;
}

// An indexed triangle list: its full mesh (in vertex cache order when `reorder`)
// cut into runs, each with copies of its vertices; the 32-bit indices of it and of
// its levels into them, and the runs' own 16-bit ones.
void uploadInRuns(const PrimitiveData& source, const std::vector<MeshLod>* levels, bool reorder, GpuPrimitive& prim) {
  const std::size_t vertices = source.positions.size();
  RunSplit split = splitIntoRuns(orderedIndices(source.indices, vertices, reorder), vertices);
  std::vector<std::vector<std::uint32_t>> levelIndices;
  for (const MeshLod& level : levels ? *levels : std::vector<MeshLod>{}) {
    prim.levels.push_back({0, GLsizei(level.indices.size()), level.error, {}});
    levelIndices.push_back(orderedIndices(level.indices, vertices, reorder));
  }
  const PrimitiveData data = verticesInSplitOrder(source, split);
  const std::vector<std::uint32_t> indices = splitIndicesWithLevels(split, levelIndices, prim);
  addVertexBuffers(data, prim);
  prim.sources.indices = addBuffer(prim, indices);
  prim.sources.runIndices = addBuffer(prim, runIndexBuffer(split));
  prim.vertexCount = GLsizei(data.positions.size());
  prim.indexCount = GLsizei(source.indices.size());
  prim.runs = std::move(split.runs);
  prim.sourceVertex = std::move(split.sourceVertex);
  addClusters(data, indices, prim);
  uploadMorphTargets(data, prim);
}

// Any other primitive: its vertices as they are, and its indices.
void uploadWhole(const PrimitiveData& data, GpuPrimitive& prim) {
  addVertexBuffers(data, prim);
  if (!data.indices.empty()) prim.sources.indices = addBuffer(prim, data.indices);
  prim.vertexCount = GLsizei(data.positions.size());
  prim.indexCount = GLsizei(data.indices.size());
  uploadMorphTargets(data, prim);
}

GpuPrimitive uploadPrimitive(const PrimitiveData& data, const std::vector<MeshLod>* levels, bool reorder) {
  GpuPrimitive prim;
  prim.influences = data.influences;
  prim.material = data.material;
  if (isIndexedTriangleList(data)) {  // drawn in runs (asset/vertex_runs.h)
    uploadInRuns(data, levels, reorder, prim);
  } else {
    uploadWhole(data, prim);
  }
  prim.vao = gl::VertexArray::create();
  attachAttributes(prim, prim.vao, nullptr);
  if (!data.positions.empty()) {
    glm::vec3 lo(data.positions[0]), hi(data.positions[0]);
    for (const glm::vec3& p : data.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    prim.center = (lo + hi) * 0.5f;
  }
  return prim;
}

gl::Texture uploadImage(const Image& image, GLenum format) {
  gl::Texture t = gl::Texture::create2D(format, image.width, image.height, 0);
  // glTF images are top row first and uv (0,0) is the top-left: upload as is.
  t.uploadRgba8(image.pixels.data());
  t.generateMipmaps();
  t.parameter(GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  t.parameter(GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  return t;
}

}  // namespace

void attachAttributes(const GpuPrimitive& prim, const gl::VertexArray& vao, const gl::Buffer* deformed) {
  const GpuPrimitive::Sources& in = prim.sources;
  auto buffer = [&prim](int index) -> const gl::Buffer& { return prim.buffers[size_t(index)]; };
  // Bindings: 0 positions, 1 normals, 2 uvs, 3 joints, 4 weights, 5 tangents,
  // 6 TEXCOORD_1; locations as scene.vert reads them.
  if (deformed) {
    constexpr GLsizei stride = 3 * sizeof(glm::vec4);  // skin.comp's DeformedVertex
    vao.vertexBuffer(0, *deformed, stride);
    vao.attribute(0, 0, 3, 0);
    vao.attribute(1, 0, 3, sizeof(glm::vec4));
    if (prim.hasTangents) vao.attribute(7, 0, 4, 2 * sizeof(glm::vec4));
  } else {
    vao.vertexBuffer(0, buffer(in.positions), sizeof(glm::vec3));
    vao.attribute(0, 0, 3, 0);
    if (in.normals >= 0) {
      vao.vertexBuffer(1, buffer(in.normals), sizeof(glm::vec3));
      vao.attribute(1, 1, 3, 0);
    } else {
      glVertexAttrib3f(1, 0.0f, 1.0f, 0.0f);  // missing normals: a constant (current) value
    }
    if (in.tangents >= 0) {
      vao.vertexBuffer(5, buffer(in.tangents), sizeof(glm::vec4));
      vao.attribute(7, 5, 4, 0);
    }
    if (in.joints >= 0) {
      const GLsizei n = prim.influences;
      vao.vertexBuffer(3, buffer(in.joints), n * GLsizei(sizeof(std::uint16_t)));
      vao.vertexBuffer(4, buffer(in.weights), n * GLsizei(sizeof(float)));
      vao.integerAttribute(3, 3, 4, 0, GL_UNSIGNED_SHORT);
      vao.attribute(4, 4, 4, 0);
      if (n == 8) {
        vao.integerAttribute(5, 3, 4, 4 * sizeof(std::uint16_t), GL_UNSIGNED_SHORT);
        vao.attribute(6, 4, 4, 4 * sizeof(float));
      }
    }
  }
  if (in.uvs >= 0) {
    vao.vertexBuffer(2, buffer(in.uvs), sizeof(glm::vec2));
    vao.attribute(2, 2, 2, 0);
  }
  if (in.uvs1 >= 0) {
    vao.vertexBuffer(6, buffer(in.uvs1), sizeof(glm::vec2));
    vao.attribute(8, 6, 2, 0);
  }
  if (in.colors >= 0) {
    vao.vertexBuffer(7, buffer(in.colors), sizeof(glm::vec4));
    vao.attribute(9, 7, 4, 0);
  }
  if (in.runIndices >= 0) {
    vao.indexBuffer(buffer(in.runIndices));
  } else if (in.indices >= 0) {
    vao.indexBuffer(buffer(in.indices));
  }
}

Result<GpuModel> GpuModel::upload(const ModelData& model, const UploadOptions& options) {
  GpuModel gpu;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    std::vector<GpuPrimitive> prims;
    for (size_t k = 0; k < model.meshes[m].primitives.size(); ++k) {
      const std::vector<MeshLod>* levels = options.levels ? &(*options.levels)[m][k] : nullptr;
      const PrimitiveData& data = model.meshes[m].primitives[k];
      prims.push_back(uploadPrimitive(data, levels, mayReorderTriangles(model, data)));
    }
    gpu.meshes_.push_back(std::move(prims));
  }
  std::vector<char> srgb(model.images.size(), 0), linear(model.images.size(), 0);
  auto use = [](std::vector<char>& used, int image) {
    if (image >= 0 && image < int(used.size())) used[size_t(image)] = 1;
  };
  for (const MaterialData& m : model.materials) {
    for (int i = 0; i < kTextureSlots; ++i) use(isSrgbSlot(TextureSlot(i)) ? srgb : linear, m.image(TextureSlot(i)));
  }
  gpu.srgbImages_.resize(model.images.size());
  gpu.linearImages_.resize(model.images.size());
  for (size_t i = 0; i < model.images.size(); ++i) {
    const Image& image = model.images[i].image;
    if (srgb[i]) gpu.srgbImages_[i] = uploadImage(image, GL_SRGB8_ALPHA8);
    if (linear[i]) gpu.linearImages_[i] = uploadImage(image, GL_RGBA8);
  }
  for (const MaterialData& m : model.materials) {
    for (const TextureSlotData& slot : m.textures) {
      if (gpu.samplers_.count(slot.sampler)) continue;
      gl::Sampler sampler = gl::Sampler::create();
      sampler.parameter(GL_TEXTURE_WRAP_S, GLint(slot.sampler.wrapS));
      sampler.parameter(GL_TEXTURE_WRAP_T, GLint(slot.sampler.wrapT));
      sampler.parameter(GL_TEXTURE_MAG_FILTER, GLint(slot.sampler.magFilter));
      sampler.parameter(GL_TEXTURE_MIN_FILTER, GLint(slot.sampler.minFilter));
      gpu.samplers_.emplace(slot.sampler, std::move(sampler));
    }
  }
  const bool sheen = std::any_of(model.materials.begin(), model.materials.end(),
                                 [](const MaterialData& m) { return m.layers.sheen(); });
  // Filtered as SheenTable::lookup filters it.
  if (sheen) gpu.sheenAlbedo_ = gl::Texture::table(GL_R32F, GL_RED, sheenTable().size, sheenTable().texels.data());
  gpu.materials_ = options.materials ? *options.materials : gltfMaterials(model);
  gpu.white_ = gl::Texture::create2D(GL_SRGB8_ALPHA8, 1, 1, 1);
  const std::uint8_t white[4] = {255, 255, 255, 255};
  gpu.white_.uploadRgba8(white);
  return gpu;
}

const gl::Texture& GpuModel::image(int image, bool srgb) const {
  const auto& images = srgb ? srgbImages_ : linearImages_;
  if (image < 0 || image >= int(images.size()) || images[size_t(image)].id() == 0) return white_;
  return images[size_t(image)];
}

const gl::Sampler& GpuModel::sampler(const SamplerData& settings) const {
  // Every material slot's settings were made on upload.
  return samplers_.at(settings);
}

}  // namespace engine
