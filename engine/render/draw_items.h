#pragma once
// The draws of one pass, built once per view after culling and sorted by one key
// (Filament's and bgfx's sort keys): opaque draws by program, then material, then
// front to back, so each program is bound once and hidden surfaces fail the depth
// test early; blended draws back to front, as "over" needs. GL-free.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

namespace engine {

struct DrawItem {
  enum class Source : std::uint8_t { Shape, Character };
  Source source = Source::Shape;
  int object = -1;  // the shape's or the character's index in the scene renderer
  int node = -1;    // a character's glTF node and primitive
  int primitive = -1;
  std::uint32_t program = 0;  // the GL program, for counting changes
  std::uint64_t key = 0;
  int surfaceGroup = -1;  // a deferred character primitive's group of one material (its stencil)
  // Its variant leaves the far sun map out (ShaderVariant::nearSunOnly): worked out
  // once when collected, for the program counted there and the one drawn.
  bool nearSunOnly = false;
};

// Non-negative floats order as their bits do; a distance is clamped to >= 0.
inline std::uint32_t distanceBits(double distance) {
  return std::bit_cast<std::uint32_t>(float(std::max(distance, 0.0)));
}

// Program (20 bits), material (12 bits), then distance (32 bits), ascending.
inline std::uint64_t opaqueKey(std::uint32_t programOrder, std::uint32_t material, double distance) {
  return std::uint64_t(programOrder & 0xFFFFFu) << 44 | std::uint64_t(material & 0xFFFu) << 32 |
         distanceBits(distance);
}

// Far first.
inline std::uint64_t blendKey(double distance) { return ~std::uint64_t(distanceBits(distance)); }

// Stable: draws of equal keys keep the order they were collected in.
inline void sortDrawItems(std::vector<DrawItem>& items) {
  std::stable_sort(items.begin(), items.end(), [](const DrawItem& a, const DrawItem& b) { return a.key < b.key; });
}

}  // namespace engine
