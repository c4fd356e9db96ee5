#pragma once
// A decoded Draco mesh, behind a small shared library (engine_draco) of its own.
//
// Why a library of its own: Debian's libdraco bundles its own, differently built
// copies of tinygltf and stb_image and exports them (libdraco.so has 49
// tinygltf:: symbols). Linked into a program beside libtinygltf, whichever comes
// first in the link or load order supplies tinygltf::* for everyone, and with
// libdraco first every glTF load corrupted the heap. engine_draco links the static
// libdraco.a with --exclude-libs,ALL, so nothing of Draco's (the bundled copies
// included) is visible outside it; only this class is.
//
// No tinygltf type crosses this interface: component types are glTF's numbers.
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/result.h"

namespace engine::gltf {

class DracoMesh {
 public:
  // Decodes a KHR_draco_mesh_compression stream (a triangle mesh). Errors carry
  // the decoder's own message ("Failed to parse Draco header.").
  static Result<DracoMesh> decode(std::span<const unsigned char> bytes);

  DracoMesh(DracoMesh&&) noexcept;
  DracoMesh& operator=(DracoMesh&&) noexcept;
  ~DracoMesh();

  std::uint32_t points() const;
  std::uint32_t triangles() const;
  // Three point indices per triangle; each is below points().
  std::vector<std::uint32_t> indices() const;

  // Draco attribute `id` (its unique id, as the extension's `attributes` name it)
  // for every point, as `components` values of glTF `componentType` (5120 BYTE
  // to 5126 FLOAT), tightly packed. Errors name the attribute id.
  Result<std::vector<unsigned char>> attribute(std::uint32_t id, int componentType, int components) const;

  // The quantization step (range / (2^bits - 1), in the attribute's units) of
  // attribute `id` in a Draco stream; 0 when it is not quantized. For tests that
  // derive their tolerances from the file.
  static Result<double> quantizationStep(std::span<const unsigned char> bytes, std::uint32_t id);

 private:
  struct Impl;
  explicit DracoMesh(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace engine::gltf
