#pragma once
// The pieces of a glTF 2.0 file both generated models share: a JSON type whose
// text is stable (insertion order, 32-bit floats printed as the shortest text that
// reads back to the same value) and a builder for the one binary buffer with its
// bufferViews and accessors.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace assetgen {

// Objects keep insertion order and numbers are 32-bit floats, so the text is stable
// and accessor min/max read back as exactly the values stored in the buffer.
using Json = nlohmann::basic_json<nlohmann::ordered_map, std::vector, std::string, bool,
                                  std::int64_t, std::uint64_t, float>;

constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
constexpr int kUnsignedByte = 5121;
constexpr int kUnsignedShort = 5123;
constexpr int kFloat = 5126;
constexpr int kLinear = 9729;
constexpr int kLinearMipmapLinear = 9987;
constexpr int kClampToEdge = 33071;
constexpr int kRepeat = 10497;

inline Json vec3Json(glm::vec3 v) { return Json::array({v.x, v.y, v.z}); }

// Collects the binary buffer and the bufferViews and accessors that describe it.
class BufferBuilder {
 public:
  explicit BufferBuilder(Json& doc) : doc_(doc) {}

  // Appends `bytes` as a new bufferView, starting on a 4-byte boundary as glTF
  // requires for float data. target and stride are left out when 0.
  int addView(const std::vector<std::uint8_t>& bytes, int target, int stride) {
    while (bin_.size() % 4 != 0) bin_.push_back(0);
    Json view = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes.size()}};
    if (stride != 0) view["byteStride"] = stride;
    if (target != 0) view["target"] = target;
    bin_.insert(bin_.end(), bytes.begin(), bytes.end());
    doc_["bufferViews"].push_back(view);
    return static_cast<int>(doc_["bufferViews"].size()) - 1;
  }

  int addAccessor(int view, size_t byteOffset, int componentType, size_t count, const char* type,
                  Json extra = Json::object()) {
    Json accessor = {{"bufferView", view}};
    if (byteOffset != 0) accessor["byteOffset"] = byteOffset;
    accessor["componentType"] = componentType;
    accessor["count"] = count;
    accessor["type"] = type;
    for (auto& [key, value] : extra.items()) accessor[key] = value;
    doc_["accessors"].push_back(accessor);
    return static_cast<int>(doc_["accessors"].size()) - 1;
  }

  // Floats in their own bufferView; `components` per element, with min and max
  // when asked (required for positions and animation times).
  int addFloats(const std::vector<float>& values, int components, const char* type, bool bounds) {
    std::vector<std::uint8_t> bytes(values.size() * sizeof(float));
    std::memcpy(bytes.data(), values.data(), bytes.size());
    const int view = addView(bytes, 0, 0);
    Json extra = Json::object();
    if (bounds) {
      extra["min"] = Json::array();
      extra["max"] = Json::array();
      for (int c = 0; c < components; ++c) {
        float lo = std::numeric_limits<float>::max(), hi = -lo;
        for (size_t i = c; i < values.size(); i += components) {
          lo = std::min(lo, values[i]);
          hi = std::max(hi, values[i]);
        }
        extra["min"].push_back(lo);
        extra["max"].push_back(hi);
      }
    }
    return addAccessor(view, 0, kFloat, values.size() / components, type, extra);
  }

  std::vector<std::uint8_t> take() { return std::move(bin_); }

 private:
  Json& doc_;
  std::vector<std::uint8_t> bin_;
};

}  // namespace assetgen
