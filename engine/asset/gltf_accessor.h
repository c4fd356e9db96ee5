#pragma once
// Generic glTF accessor reading (internal to engine_asset): every component type,
// normalised integers, interleaved buffer views (byteStride) and sparse accessors,
// with every offset checked against its bufferView and buffer.
#include <cstddef>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "core/result.h"

namespace engine::gltf {

struct AccessorValues {
  std::size_t count = 0;   // elements
  int components = 0;      // per element: 1 SCALAR, 2 VEC2, ... 16 MAT4
  std::vector<double> values;  // count * components; double holds every type exactly
  double at(std::size_t element, int component) const {
    return values[element * static_cast<std::size_t>(components) + static_cast<std::size_t>(component)];
  }
};

// `context` prefixes errors, e.g. "hero.glb: mesh 0 primitive 1 POSITION".
// Bytes of one component of a glTF componentType (BYTE ... FLOAT); 0 for others.
int componentBytes(int componentType);

Result<AccessorValues> readAccessor(const tinygltf::Model& model, int index,
                                    const std::string& context);

}  // namespace engine::gltf
