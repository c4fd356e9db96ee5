#pragma once
// The GPU skin cache (Unreal's, and the course's GPGPU part): every primitive
// instance that deforms (skinned and/or morphed) is deformed once per pose by a
// compute shader (shaders/skin.comp) into a vertex buffer of its own, and every
// pass (both sun maps, the point light's six faces, the probes, the main view)
// draws that buffer as a static mesh. Without it each pass skins every vertex
// again in its vertex shader.
#include <array>
#include <map>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "asset/model_data.h"
#include "core/result.h"
#include "gl/resources.h"
#include "gl/shader.h"
#include "render/gpu_model.h"

namespace engine {

// The compute programs of skin.comp, one per variant, built when first used.
class SkinPrograms {
 public:
  explicit SkinPrograms(std::string shaderDir) : shaderDir_(std::move(shaderDir)) {}
  struct Variant {
    int influences = 0;  // 0: not skinned (a morph only), 4 or 8
    SkinMode mode = SkinMode::Linear;
    bool morph = false;
    bool normals = false;
    bool tangents = false;
    auto operator<=>(const Variant&) const = default;
    std::string describe() const;
  };
  Result<const gl::Program*> get(const Variant& variant);
  std::vector<Variant> built() const;

 private:
  std::string shaderDir_;
  std::map<Variant, gl::Program> programs_;
};

// One model instance's cache: an output buffer and a vertex array for every
// (node, primitive) that deforms.
class SkinCache {
 public:
  SkinCache() = default;
  // The entries of `model`'s deforming primitives, drawn by `gpu` (needs a context).
  static SkinCache create(const ModelData& model, const GpuModel& gpu);

  // What one update reads: the instance's uploaded skin palettes (one buffer
  // texture per skin, in `mode`'s layout) and morph weights.
  struct Inputs {
    std::span<const gl::Texture> skinPalettes;
    SkinMode mode = SkinMode::Linear;
    const gl::Buffer* morphWeights = nullptr;
    std::span<const int> morphFirst;  // per glTF node, -1: no morph
  };
  // Deforms every entry for the pose the inputs hold, then makes the writes
  // visible to vertex fetching.
  Status update(SkinPrograms& programs, const ModelData& model, const GpuModel& gpu, const Inputs& inputs);

  // The deformed vertex array of primitive `primitive` of node `node`, or nullptr
  // where the primitive does not deform.
  const gl::VertexArray* vertexArray(int node, int primitive) const;
  // Its output (tests read it back): three vec4 per vertex, as skin.comp writes.
  const gl::Buffer* output(int node, int primitive) const;
  int entries() const { return int(entries_.size()); }
  std::size_t bytes() const;  // of every output buffer
  // Vertices deformed by the last update.
  long long verticesDeformed() const { return verticesDeformed_; }

 private:
  struct Entry {
    int node = -1;
    int primitive = -1;
    gl::Buffer output;
    gl::VertexArray vao;
    std::array<gl::Texture, 5> sources;  // the primitive's vertex buffers as skin.comp reads them
  };
  const Entry* find(int node, int primitive) const;
  Status run(SkinPrograms& programs, const ModelData& model, const GpuModel& gpu, const Inputs& inputs,
             const Entry& entry);

  std::vector<Entry> entries_;  // by node, then primitive
  long long verticesDeformed_ = 0;
};

// Whether primitive `prim` of `node` deforms: skinned (not in SkinMode::None) or
// morphed.
bool deforms(const NodeData& node, const PrimitiveData& prim);

}  // namespace engine
