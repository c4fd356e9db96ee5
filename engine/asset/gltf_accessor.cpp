#include "asset/gltf_accessor.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "asset/gltf_limits.h"

namespace engine::gltf {
namespace {

constexpr std::size_t kMaxZeroAccessorValues = 1u << 24;


int typeComponents(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
  }
}

template <typename T>
T load(const unsigned char* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

// glTF's normalised-integer rule: signed types clamp at -1 so that both -127 and
// -128 map to -1.
double readComponent(const unsigned char* p, int componentType, bool normalized) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      double v = load<std::int8_t>(p);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      double v = load<std::uint8_t>(p);
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      double v = load<std::int16_t>(p);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      double v = load<std::uint16_t>(p);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load<std::uint32_t>(p);
    default: return load<float>(p);
  }
}

// A validated window into a buffer: `count` elements of `elementBytes`, `stride` apart.
struct View {
  const unsigned char* data = nullptr;
  std::size_t stride = 0;
};

// Checks that bufferView `viewIndex` lies inside its buffer and that `count`
// elements of `elementBytes` starting at `offset` (with the view's stride, or
// tightly packed) lie inside the view.
Result<View> resolveView(const tinygltf::Model& model, int viewIndex, std::size_t offset,
                         std::size_t count, std::size_t elementBytes, bool allowStride,
                         const std::string& context) {
  if (viewIndex < 0 || static_cast<std::size_t>(viewIndex) >= model.bufferViews.size())
    return makeError(context + ": bufferView " + std::to_string(viewIndex) + " does not exist");
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(viewIndex)];
  std::string viewName = context + ": bufferView " + std::to_string(viewIndex);
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
    return makeError(viewName + ": buffer " + std::to_string(view.buffer) + " does not exist");
  const tinygltf::Buffer& buffer = model.buffers[static_cast<std::size_t>(view.buffer)];
  std::size_t bufferBytes = buffer.data.size();
  if (view.byteOffset > bufferBytes || view.byteLength > bufferBytes - view.byteOffset)
    return makeError(viewName + ": bytes [" + std::to_string(view.byteOffset) + ", " +
                     std::to_string(view.byteOffset + view.byteLength) + ") run past buffer " +
                     std::to_string(view.buffer) + " of " + std::to_string(bufferBytes) +
                     " bytes");
  std::size_t stride = elementBytes;
  if (allowStride && view.byteStride != 0) {
    if (view.byteStride < elementBytes || view.byteStride > 252)
      return makeError(viewName + ": byteStride " + std::to_string(view.byteStride) +
                       " is invalid for elements of " + std::to_string(elementBytes) + " bytes");
    stride = view.byteStride;
  }
  // count <= kMaxAccessorElements and stride <= 252, so this cannot overflow.
  std::uint64_t needed = offset + static_cast<std::uint64_t>(stride) * (count - 1) + elementBytes;
  if (offset > view.byteLength || needed > view.byteLength)
    return makeError(context + ": needs " + std::to_string(needed) + " bytes but bufferView " +
                     std::to_string(viewIndex) + " has " + std::to_string(view.byteLength));
  return View{buffer.data.data() + view.byteOffset + offset, stride};
}

Status applySparse(const tinygltf::Model& model, const tinygltf::Accessor& accessor,
                   AccessorValues& out, const std::string& context) {
  const auto& sparse = accessor.sparse;
  if (sparse.count < 1 || static_cast<std::size_t>(sparse.count) > accessor.count)
    return makeError(context + ": sparse count " + std::to_string(sparse.count) +
                     " is outside [1, " + std::to_string(accessor.count) + "]");
  std::size_t count = static_cast<std::size_t>(sparse.count);
  int indexBytes = componentBytes(sparse.indices.componentType);
  if (indexBytes == 0 || sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
      sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_SHORT ||
      sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
    return makeError(context + ": sparse indices have an invalid component type");
  if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0)
    return makeError(context + ": sparse byteOffset is negative");
  auto indices = resolveView(model, sparse.indices.bufferView,
                             static_cast<std::size_t>(sparse.indices.byteOffset), count,
                             static_cast<std::size_t>(indexBytes), false, context + ": sparse indices");
  if (!indices) return indices.error();
  int elementBytes = componentBytes(accessor.componentType) * out.components;
  auto values = resolveView(model, sparse.values.bufferView,
                            static_cast<std::size_t>(sparse.values.byteOffset), count,
                            static_cast<std::size_t>(elementBytes), false, context + ": sparse values");
  if (!values) return values.error();
  int componentSize = componentBytes(accessor.componentType);
  for (std::size_t i = 0; i < count; ++i) {
    double target = readComponent(indices->data + i * static_cast<std::size_t>(indexBytes),
                                  sparse.indices.componentType, false);
    if (target >= static_cast<double>(accessor.count))
      return makeError(context + ": sparse index " + std::to_string(static_cast<std::uint64_t>(target)) +
                       " is past the accessor's " + std::to_string(accessor.count) + " elements");
    std::size_t element = static_cast<std::size_t>(target);
    const unsigned char* src = values->data + i * static_cast<std::size_t>(elementBytes);
    for (int c = 0; c < out.components; ++c)
      out.values[element * static_cast<std::size_t>(out.components) + static_cast<std::size_t>(c)] =
          readComponent(src + c * componentSize, accessor.componentType, accessor.normalized);
  }
  return Ok{};
}

}  // namespace

Result<AccessorValues> readAccessor(const tinygltf::Model& model, int index,
                                    const std::string& context) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
    return makeError(context + ": accessor " + std::to_string(index) + " does not exist");
  const tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(index)];
  std::string name = context + ": accessor " + std::to_string(index);
  AccessorValues out;
  out.components = typeComponents(accessor.type);
  int componentSize = componentBytes(accessor.componentType);
  if (out.components == 0 || componentSize == 0)
    return makeError(name + ": unknown type or componentType");
  if (accessor.count < 1 || accessor.count > kMaxAccessorElements)
    return makeError(name + ": count " + std::to_string(accessor.count) + " is outside [1, " +
                     std::to_string(kMaxAccessorElements) + "]");
  out.count = accessor.count;
  std::size_t valueCount = out.count * static_cast<std::size_t>(out.components);
  // Without a bufferView the accessor is all zeros (then usually sparse); its
  // size is only a number in the JSON, so it gets a tighter bound than data
  // that must actually be present in the file.
  if (accessor.bufferView < 0) {
    if (valueCount > kMaxZeroAccessorValues)
      return makeError(name + ": " + std::to_string(valueCount) + " values without a bufferView, the limit is " +
                       std::to_string(kMaxZeroAccessorValues));
    out.values.assign(valueCount, 0.0);
  } else {
    std::size_t elementBytes = static_cast<std::size_t>(componentSize * out.components);
    auto view = resolveView(model, accessor.bufferView, accessor.byteOffset, out.count,
                            elementBytes, true, name);
    if (!view) return view.error();
    out.values.assign(valueCount, 0.0);
    for (std::size_t i = 0; i < out.count; ++i) {
      const unsigned char* src = view->data + i * view->stride;
      for (int c = 0; c < out.components; ++c)
        out.values[i * static_cast<std::size_t>(out.components) + static_cast<std::size_t>(c)] =
            readComponent(src + c * componentSize, accessor.componentType, accessor.normalized);
    }
  }
  if (accessor.sparse.isSparse) {
    Status sparse = applySparse(model, accessor, out, name);
    if (!sparse) return sparse.error();
  }
  return out;
}

int componentBytes(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

}  // namespace engine::gltf
