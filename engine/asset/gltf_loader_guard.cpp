// The input's guard: the file's size, the GLB container and the raw JSON
// (extensions, URIs, image views, count limits) are checked before tinygltf
// parses anything, and tinygltf reads files only through guardedReadWholeFile.
#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "asset/gltf_loader_impl.h"

namespace engine {
namespace {

namespace fs = std::filesystem;

}  // namespace

namespace gltf_loader {

Result<std::vector<unsigned char>> readFileBytes(const std::string& path) {
  std::error_code ec;
  std::uintmax_t size = fs::file_size(path, ec);
  if (ec) return makeError(path + ": cannot open: " + ec.message());
  if (size > kMaxModelFileBytes)
    return makeError(path + ": file is " + std::to_string(size) + " bytes, the limit is " +
                     std::to_string(kMaxModelFileBytes));
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
  if (!in || !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
    return makeError(path + ": cannot read the file");
  return bytes;
}

// Checks the GLB container before tinygltf sees it, so that a truncated file gets
// a message saying what is missing, and returns the JSON chunk's text.
Result<std::string> glbJson(const std::vector<unsigned char>& bytes, const std::string& path) {
  if (bytes.size() < 20) return makeError(path + ": truncated GLB: " + str(bytes.size()) + " bytes, the header needs 20");
  if (readU32(bytes, 0) != kGlbMagic) return makeError(path + ": not a GLB file (bad magic)");
  if (readU32(bytes, 4) != 2) return makeError(path + ": GLB version " + std::to_string(readU32(bytes, 4)) + " is not 2");
  std::uint64_t length = readU32(bytes, 8);
  if (length > bytes.size())
    return makeError(path + ": truncated GLB: header says " + std::to_string(length) +
                     " bytes, the file has " + str(bytes.size()));
  std::uint64_t jsonLength = readU32(bytes, 12);
  if (readU32(bytes, 16) != kGlbJsonChunk) return makeError(path + ": GLB chunk 0 is not JSON");
  if (20 + jsonLength > length)
    return makeError(path + ": truncated GLB: JSON chunk of " + std::to_string(jsonLength) +
                     " bytes runs past the end");
  std::uint64_t binStart = 20 + ((jsonLength + 3) & ~std::uint64_t{3});
  if (binStart + 8 <= length) {
    std::uint64_t binLength = readU32(bytes, static_cast<std::size_t>(binStart));
    if (binStart + 8 + binLength > length)
      return makeError(path + ": truncated GLB: BIN chunk of " + std::to_string(binLength) +
                       " bytes runs past the end");
  }
  return std::string(reinterpret_cast<const char*>(bytes.data() + 20), static_cast<std::size_t>(jsonLength));
}

// `bytes` (a GLB checked by glbJson) with its JSON chunk replaced by `json`; the
// chunks after it are kept as they are.
std::vector<unsigned char> withGlbJson(const std::vector<unsigned char>& bytes, std::string json) {
  json.append((4 - json.size() % 4) % 4, ' ');  // chunks are 4-byte aligned, JSON padded with spaces
  const std::size_t oldJson = readU32(bytes, 12);
  const std::size_t rest = std::min(bytes.size(), static_cast<std::size_t>(readU32(bytes, 8)));
  const std::size_t tail = std::min(rest, 20 + ((oldJson + 3) & ~std::size_t{3}));
  std::vector<unsigned char> out(20 + json.size() + (rest - tail));
  auto put = [&](std::size_t at, std::uint32_t v) { std::memcpy(out.data() + at, &v, 4); };
  std::memcpy(out.data(), bytes.data(), 8);
  put(8, static_cast<std::uint32_t>(out.size()));
  put(12, static_cast<std::uint32_t>(json.size()));
  put(16, kGlbJsonChunk);
  std::memcpy(out.data() + 20, json.data(), json.size());
  std::copy(bytes.begin() + static_cast<std::ptrdiff_t>(tail), bytes.begin() + static_cast<std::ptrdiff_t>(rest),
            out.begin() + static_cast<std::ptrdiff_t>(20 + json.size()));
  return out;
}

namespace {

std::string percentDecode(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && std::isxdigit(static_cast<unsigned char>(s[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(s[i + 2]))) {
      out += static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

// A model may only read files in or below its own folder: a URI with a scheme,
// an absolute path or a ".." segment could make a downloaded model read any file.
bool uriStaysInFolder(const std::string& uri) {
  if (uri.rfind("data:", 0) == 0) return true;
  std::string path = percentDecode(uri);
  if (path.empty() || path[0] == '/' || path[0] == '\\') return false;
  if (path.find(':') != std::string::npos) return false;  // scheme or drive letter
  std::size_t start = 0;
  while (start <= path.size()) {
    std::size_t end = path.find_first_of("/\\", start);
    if (end == std::string::npos) end = path.size();
    if (path.compare(start, end - start, "..") == 0 && end - start == 2) return false;
    start = end + 1;
  }
  return true;
}

// The glTF extensions this loader implements. KHR_mesh_quantization needs nothing
// of its own: every accessor is read with its component type and normalisation.
// The two compressions are decoded into plain buffers after tinygltf
// (gltf_compression.h). EXT_mesh_gpu_instancing becomes NodeData::instances,
// KHR_lights_punctual ModelData::lights (placed by asset/model_lights.h).
const std::set<std::string>& supportedExtensions() {
  static const std::set<std::string> supported{"KHR_mesh_quantization", "KHR_materials_emissive_strength",
                                               "KHR_materials_unlit", "KHR_materials_ior",
                                               "KHR_materials_specular", "KHR_materials_clearcoat",
                                               "KHR_materials_transmission", "KHR_materials_volume",
                                               "KHR_texture_transform", "KHR_draco_mesh_compression",
                                               "EXT_meshopt_compression", "EXT_mesh_gpu_instancing",
                                               "KHR_lights_punctual", "KHR_materials_variants",
                                               "KHR_materials_sheen", "KHR_materials_anisotropy",
                                               "KHR_materials_iridescence"};
  return supported;
}

// The names in `doc[key]` (a list of strings) that this loader does not implement.
std::vector<std::string> unsupportedExtensions(const nlohmann::json& doc, const char* key) {
  std::vector<std::string> names;
  auto list = doc.find(key);
  if (list == doc.end() || !list->is_array()) return names;
  for (const auto& name : *list) {
    if (name.is_string() && !supportedExtensions().count(name.get<std::string>())) names.push_back(name.get<std::string>());
  }
  return names;
}

// Checked on the raw JSON, before tinygltf: a required extension changes what the
// data means (an unknown compression's accessors would read as zeros or as bytes
// that are not theirs). Required and unsupported: an error listing them all. Used
// but optional: a warning each, and the model is read without them.
Status checkExtensions(const nlohmann::json& doc, const std::string& path, std::vector<std::string>& warnings) {
  const auto required = unsupportedExtensions(doc, "extensionsRequired");
  if (!required.empty()) {
    return makeError(path + ": requires " + joined(required) + ", which this engine does not support");
  }
  for (const std::string& name : unsupportedExtensions(doc, "extensionsUsed")) {
    warnings.push_back(path + ": uses " + name + ", which this engine does not support; drawn without it");
  }
  return Ok{};
}

}  // namespace

// Looks at the raw JSON before tinygltf parses it or follows any URI: extensions,
// URIs, image views and the count limits.
Status checkRawJson(const std::string& jsonText, const std::string& path, std::vector<std::string>& warnings) {
  nlohmann::json doc = nlohmann::json::parse(jsonText, nullptr, false);
  if (doc.is_discarded()) return makeError(path + ": invalid JSON");
  if (!doc.is_object()) return makeError(path + ": the top-level JSON value is not an object");
  if (auto s = checkExtensions(doc, path, warnings); !s) return s;
  // The count limits are checked here as well as after parsing: tinygltf spends
  // about 1 KiB per node, so a 3 MiB list of empty nodes would cost a gigabyte
  // before Converter::checkLimits could refuse it.
  // tinygltf hands an image's bufferView to the image loader without checking that
  // it lies inside its buffer (the loader would read past the end), so the views
  // of images are checked against the declared buffer sizes here; tinygltf checks
  // the declared sizes against the data.
  auto images = doc.find("images");
  auto views = doc.find("bufferViews");
  auto buffers = doc.find("buffers");
  if (images != doc.end() && images->is_array())
    for (std::size_t i = 0; i < images->size(); ++i) {
      const auto& image = (*images)[i];
      if (!image.is_object() || !image.contains("bufferView")) continue;
      const auto& v = image["bufferView"];
      std::string name = path + ": image " + str(i) + ": bufferView ";
      if (!v.is_number_unsigned() || views == doc.end() || !views->is_array() || v.get<std::uint64_t>() >= views->size())
        return makeError(name + v.dump() + " does not exist");
      const auto& view = (*views)[v.get<std::size_t>()];
      auto field = [&](const nlohmann::json& o, const char* key, std::uint64_t fallback) -> std::int64_t {
        if (!o.is_object() || !o.contains(key)) return static_cast<std::int64_t>(fallback);
        return o[key].is_number_unsigned() && o[key].get<std::uint64_t>() < (1ull << 62) ? o[key].get<std::int64_t>() : -1;
      };
      std::int64_t b = field(view, "buffer", ~0ull >> 2), offset = field(view, "byteOffset", 0), bytes = field(view, "byteLength", 0);
      if (b < 0 || offset < 0 || bytes < 0 || buffers == doc.end() || !buffers->is_array() ||
          static_cast<std::uint64_t>(b) >= buffers->size())
        return makeError(name + v.dump() + " is malformed or names no buffer");
      std::int64_t size = field((*buffers)[static_cast<std::size_t>(b)], "byteLength", 0);
      if (size < 0 || offset + bytes > size)
        return makeError(name + v.dump() + ": bytes [" + std::to_string(offset) + ", " + std::to_string(offset + bytes) +
                         ") run past buffer " + std::to_string(b) + " of " + std::to_string(size) + " bytes");
    }
  if (auto nodes = doc.find("nodes"); nodes != doc.end() && nodes->is_array() && nodes->size() > kMaxNodes)
    return makeError(path + ": " + str(nodes->size()) + " nodes, the limit is " + str(kMaxNodes));
  if (auto skins = doc.find("skins"); skins != doc.end() && skins->is_array())
    for (std::size_t i = 0; i < skins->size(); ++i) {
      const auto& skin = (*skins)[i];
      if (skin.is_object() && skin.contains("joints") && skin["joints"].is_array() &&
          skin["joints"].size() > kMaxSkinJoints)
        return makeError(path + ": skin " + str(i) + ": " + str(skin["joints"].size()) +
                         " joints, the limit is " + str(kMaxSkinJoints));
    }
  for (const char* kind : {"buffers", "images"}) {
    auto list = doc.find(kind);
    if (list == doc.end() || !list->is_array()) continue;
    for (std::size_t i = 0; i < list->size(); ++i) {
      const auto& item = (*list)[i];
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      std::string uri = item["uri"].get<std::string>();
      if (!uriStaysInFolder(uri))
        return makeError(path + ": " + std::string(kind, std::strlen(kind) - 1) + " " + str(i) +
                         ": uri \"" + uri + "\" leaves the model's folder; refused");
    }
  }
  return Ok{};
}

// tinygltf's file reader, restricted to the model's folder: the second line of
// defence after checkRawJson (tinygltf also searches the working directory).
bool guardedReadWholeFile(std::vector<unsigned char>* out, std::string* err,
                          const std::string& filepath, void* userData) {
  const fs::path& folder = *static_cast<const fs::path*>(userData);
  if (folder.empty()) {
    if (err) *err += filepath + ": a model read from memory cannot refer to files";
    return false;
  }
  std::error_code ec;
  fs::path full = fs::weakly_canonical(filepath, ec);
  if (ec) {
    if (err) *err += "cannot resolve " + filepath;
    return false;
  }
  auto rel = full.lexically_relative(folder);
  if (rel.empty() || *rel.begin() == "..") {
    if (err) *err += filepath + " is outside the model's folder";
    return false;
  }
  auto size = fs::file_size(full, ec);
  if (ec || size > kMaxModelFileBytes) {
    if (err) *err += filepath + (ec ? " cannot be read" : " is too large");
    return false;
  }
  return tinygltf::ReadWholeFile(out, err, full.string(), nullptr);
}

Status Converter::checkLimits() {
  if (gltf_.nodes.size() > kMaxNodes)
    return error(str(gltf_.nodes.size()) + " nodes, the limit is " + str(kMaxNodes));
  for (std::size_t i = 0; i < gltf_.skins.size(); ++i)
    if (gltf_.skins[i].joints.size() > kMaxSkinJoints)
      return error("skin " + str(i) + ": " + str(gltf_.skins[i].joints.size()) +
                   " joints, the limit is " + str(kMaxSkinJoints));
  return Ok{};
}

}  // namespace gltf_loader
}  // namespace engine
