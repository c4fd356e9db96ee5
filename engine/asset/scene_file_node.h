#pragma once
// The scene file reader's pieces (asset/scene_file.cpp, scene_file_media.cpp): a
// JSON value that knows its file and path for messages, and readers of numbers,
// vectors, names and enums that leave `out` as it is when the key is absent.
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "asset/scene_desc.h"
#include "core/result.h"

namespace engine::scenefile {
using nlohmann::json;

// A JSON value with the file name and its path, for messages, and the keys it
// may hold, so that unknown keys are reported.
class Node {
 public:
  Node(const json& value, std::string file, std::string path)
      : value_(value), file_(std::move(file)), path_(std::move(path)) {}

  Error error(const std::string& what) const {
    return makeError(file_ + ": " + (path_.empty() ? "/" : path_) + ": " + what);
  }
  bool has(const char* key) const { return value_.is_object() && value_.contains(key); }
  Node at(const char* key) const { return Node(value_.at(key), file_, path_ + "/" + key); }
  Node at(size_t i) const { return Node(value_.at(i), file_, path_ + "/" + std::to_string(i)); }
  const json& value() const { return value_; }
  const std::string& file() const { return file_; }

  Status expectObject(std::initializer_list<const char*> allowed) const {
    if (!value_.is_object()) return error("expected an object");
    std::set<std::string> keys(allowed.begin(), allowed.end());
    for (const auto& item : value_.items()) {
      if (!keys.count(item.key())) {
        std::string list;
        for (const auto& k : keys) list += (list.empty() ? "" : ", ") + k;
        return Node(item.value(), file_, path_ + "/" + item.key()).error("unknown key; expected one of: " + list);
      }
    }
    return Ok{};
  }
  Result<size_t> arraySize() const {
    if (!value_.is_array()) return error("expected an array");
    return value_.size();
  }

 private:
  const json& value_;
  std::string file_;
  std::string path_;
};

#define TRY(expr)                        \
  do {                                   \
    if (auto s_ = (expr); !s_) return s_.error(); \
  } while (0)

inline Status readNumber(const Node& parent, const char* key, double& out, double lo, double hi) {
  if (!parent.has(key)) return Ok{};
  const Node n = parent.at(key);
  if (!n.value().is_number()) return n.error("expected a number");
  const double v = n.value().get<double>();
  if (!std::isfinite(v) || v < lo || v > hi) {
    std::ostringstream ss;
    ss << "expected a number in [" << lo << ", " << hi << "], got " << v;
    return n.error(ss.str());
  }
  out = v;
  return Ok{};
}

inline Status readFloat(const Node& parent, const char* key, float& out, double lo, double hi) {
  double v = out;
  TRY(readNumber(parent, key, v, lo, hi));
  out = float(v);
  return Ok{};
}

inline Status readInt(const Node& parent, const char* key, int& out, int lo, int hi) {
  if (!parent.has(key)) return Ok{};
  const Node n = parent.at(key);
  if (!n.value().is_number_integer()) return n.error("expected an integer");
  const auto v = n.value().get<long long>();
  if (v < lo || v > hi) return n.error("expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  out = int(v);
  return Ok{};
}

inline Status readBool(const Node& parent, const char* key, bool& out) {
  if (!parent.has(key)) return Ok{};
  const Node n = parent.at(key);
  if (!n.value().is_boolean()) return n.error("expected true or false");
  out = n.value().get<bool>();
  return Ok{};
}

inline Status readString(const Node& parent, const char* key, std::string& out) {
  if (!parent.has(key)) return Ok{};
  const Node n = parent.at(key);
  if (!n.value().is_string()) return n.error("expected a string");
  out = n.value().get<std::string>();
  return Ok{};
}

template <typename Vec>
Status readVec3(const Node& parent, const char* key, Vec& out) {
  if (!parent.has(key)) return Ok{};
  const Node n = parent.at(key);
  if (!n.value().is_array() || n.value().size() != 3) return n.error("expected an array of 3 numbers");
  for (size_t i = 0; i < 3; ++i) {
    const Node c = n.at(i);
    if (!c.value().is_number() || !std::isfinite(c.value().get<double>())) return c.error("expected a finite number");
    // Coordinates beyond 1e12 m are no scene (the solar system fits in 1e13): sums
    // and differences of such values would overflow to infinity and NaN.
    if (std::abs(c.value().get<double>()) > 1e12) return c.error("expected a number within +-1e12");
    out[int(i)] = typename Vec::value_type(c.value().get<double>());
  }
  return Ok{};
}

template <typename Vec>
Status readDirection(const Node& parent, const char* key, Vec& out) {
  TRY(readVec3(parent, key, out));
  if (parent.has(key)) {
    if (glm::length(glm::dvec3(out)) == 0.0) return parent.at(key).error("a direction must not be zero");
    out = glm::normalize(out);
  }
  return Ok{};
}

template <typename Enum>
Status readEnum(const Node& parent, const char* key, Enum& out, const std::map<std::string, Enum>& names) {
  if (!parent.has(key)) return Ok{};
  const Node n = parent.at(key);
  std::string list;
  for (const auto& [name, value] : names) list += (list.empty() ? "" : ", ") + name;
  if (!n.value().is_string()) return n.error("expected one of: " + list);
  auto it = names.find(n.value().get<std::string>());
  if (it == names.end()) return n.error("\"" + n.value().get<std::string>() + "\" is not one of: " + list);
  out = it->second;
  return Ok{};
}

// Scattering and absorption per metre: each component finite, in [0, 1e6].
Status readCoefficients(const Node& parent, const char* key, glm::vec3& out);

// The scene's media (scene_file_media.cpp): the fog, the atmosphere, bounded media.
Status readFog(const Node& fog, FogDesc& out);
Status readAtmosphere(const Node& n, AtmosphereDesc& out);
Status readMedium(const Node& n, MediumDesc& out);

}  // namespace engine::scenefile
