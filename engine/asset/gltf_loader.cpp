#include "asset/gltf_loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string_view>
#include <utility>

#include <nlohmann/json.hpp>
#include <set>
#include <tbb/parallel_for.h>
#include <tiny_gltf.h>

#include "asset/gltf_accessor.h"
#include "asset/gltf_compression.h"
#include "asset/material_variants.h"
#include "asset/tangents.h"
#include "asset/texture_transform.h"
#include "core/log.h"
#include "core/math.h"

namespace engine {
namespace {

namespace fs = std::filesystem;
using gltf::AccessorValues;
using gltf::readAccessor;

constexpr std::uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr std::uint32_t kGlbJsonChunk = 0x4E4F534A;  // "JSON"

std::string str(std::size_t i) { return std::to_string(i); }
std::string str(int i) { return std::to_string(i); }

// How errors name an element: its kind and index, and its name when it has one
// ("material 2 (\"paint\")").
std::string labelled(const char* kind, std::size_t index, const std::string& name) {
  return std::string(kind) + " " + std::to_string(index) + (name.empty() ? "" : " (\"" + name + "\")");
}

bool validIndex(int index, std::size_t size) {
  return index >= 0 && static_cast<std::size_t>(index) < size;
}

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

std::uint32_t readU32(const std::vector<unsigned char>& bytes, std::size_t offset) {
  std::uint32_t v = 0;
  std::memcpy(&v, bytes.data() + offset, 4);
  return v;  // GLB is little-endian, as is every platform we build for
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

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
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


std::uint32_t bigEndian(const unsigned char* p, int bytes) {
  std::uint32_t v = 0;
  for (int i = 0; i < bytes; ++i) v = (v << 8) | p[i];
  return v;
}

// Width and height from a PNG or JPEG header, or {0, 0} when not found. Read
// before decoding so that a tiny file claiming 60000 x 60000 pixels is refused
// instead of allocating gigabytes.
std::pair<std::uint32_t, std::uint32_t> imageSize(const unsigned char* bytes, std::size_t size) {
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (size >= 24 && std::memcmp(bytes, kPng, 8) == 0) return {bigEndian(bytes + 16, 4), bigEndian(bytes + 20, 4)};
  if (size < 4 || bytes[0] != 0xFF || bytes[1] != 0xD8) return {0, 0};
  std::size_t at = 2;
  while (at + 9 < size && bytes[at] == 0xFF) {
    unsigned char marker = bytes[at + 1];
    bool startOfFrame = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (startOfFrame) return {bigEndian(bytes + at + 7, 2), bigEndian(bytes + at + 5, 2)};
    at += 2 + bigEndian(bytes + at + 2, 2);
  }
  return {0, 0};
}

// Decoding failures only warn: a model without its texture is still worth showing.
bool tolerantImageLoader(tinygltf::Image* image, const int imageIndex, std::string* err,
                         std::string* warn, int reqWidth, int reqHeight,
                         const unsigned char* bytes, int size, void*) {
  const std::size_t length = size > 0 ? static_cast<std::size_t>(size) : 0;
  const std::string name = "image " + std::to_string(imageIndex);
  auto refuse = [&](const std::string& why) {
    if (warn) *warn += name + ": " + why + "\n";
    image->image.clear();
    return true;
  };
  // glTF allows PNG and JPEG only. stb would also try TGA (which has no magic),
  // PSD, HDR, ... and could take any corrupted bytes for one of them, with a size
  // that nothing here has checked.
  const bool png = length >= 8 && bytes[0] == 0x89 && bytes[1] == 'P';
  const bool jpeg = length >= 4 && bytes[0] == 0xFF && bytes[1] == 0xD8;
  if (!png && !jpeg) return refuse("not a PNG or JPEG file");
  auto [width, height] = imageSize(bytes, length);
  // The same limits as readPng (core/image.h).
  if (width > static_cast<std::uint32_t>(kMaxImageSide) || height > static_cast<std::uint32_t>(kMaxImageSide))
    return refuse(std::to_string(width) + " x " + std::to_string(height) + " pixels is over the limit of " +
                  std::to_string(kMaxImageSide));
  if (std::uint64_t{width} * height > kMaxImagePixels)
    return refuse(std::to_string(width) + " x " + std::to_string(height) + " pixels is over the limit of " +
                  std::to_string(kMaxImagePixels) + " pixels");
  if (jpeg && (width == 0 || height == 0)) return refuse("JPEG without a frame header");
  if (png) {
    if (Status s = checkPngHeader(std::span(bytes, length), name); !s) {
      if (warn) *warn += s.error().message + "\n";
      image->image.clear();
      return true;
    }
  }
  std::vector<std::uint8_t> padded;
  const auto checked = png ? withFullPalette(std::span(bytes, length), padded) : std::span(bytes, length);
  // Decoded after parsing, every image at once (decodeImages): kept encoded here.
  image->image.assign(checked.begin(), checked.end());
  image->as_is = true;
  (void)err;
  (void)reqWidth;
  (void)reqHeight;
  return true;
}

// The images tolerantImageLoader kept encoded, decoded in parallel (stb decodes one
// image on one thread: DamagedHelmet's five 2048^2 textures took 0.3 s one after the
// other); a failure warns as the loader does, in the images' order.
void decodeImages(tinygltf::Model& model, const std::string& path, std::vector<std::string>& warnings) {
  std::vector<std::string> failures(model.images.size());
  tbb::parallel_for(std::size_t(0), model.images.size(), [&](std::size_t i) {
    tinygltf::Image& image = model.images[i];
    if (!image.as_is || image.image.empty()) return;
    tinygltf::Image decoded;
    std::string error, warn;
    const bool ok = tinygltf::LoadImageData(&decoded, static_cast<int>(i), &error, &warn, 0, 0, image.image.data(),
                                            static_cast<int>(image.image.size()), nullptr);
    if (ok) {
      image.width = decoded.width;
      image.height = decoded.height;
      image.component = decoded.component;
      image.bits = decoded.bits;
      image.pixel_type = decoded.pixel_type;
      image.image = std::move(decoded.image);
    } else {
      image.image.clear();
      failures[i] = "image " + std::to_string(i) + ": cannot decode: " + error;
    }
    image.as_is = false;
  });
  for (const std::string& failure : failures)
    if (!failure.empty()) warnings.push_back(path + ": " + failure);
}

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    if (end > start) lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

// `folder` is where external URIs resolve; empty for in-memory input, which may
// not read any file.
Result<tinygltf::Model> parseWithTinygltf(const std::vector<unsigned char>& bytes, const std::string& path,
                                          const fs::path& folder, ModelData& out) {
  if (bytes.size() > kMaxModelFileBytes)
    return makeError(path + ": " + str(bytes.size()) + " bytes, the limit is " + std::to_string(kMaxModelFileBytes));
  bool binary = bytes.size() >= 4 && readU32(bytes, 0) == kGlbMagic;
  // Without the magic the bytes are read as JSON text; a .glb name says what was
  // meant, and "invalid JSON" would mislead.
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (!binary && ext == ".glb") {
    if (bytes.size() < 4) return makeError(path + ": truncated GLB: " + str(bytes.size()) + " bytes, the header needs 20");
    return makeError(path + ": not a GLB file (bad magic)");
  }
  std::string jsonText;
  if (binary) {
    auto json = glbJson(bytes, path);
    if (!json) return json.error();
    jsonText = std::move(json.value());
  } else {
    jsonText.assign(bytes.begin(), bytes.end());
  }
  Status raw = checkRawJson(jsonText, path, out.warnings);
  if (!raw) return raw.error();
  // Compressed models hold things tinygltf refuses; they get placeholders first
  // (the search keeps other files from being parsed twice).
  std::vector<unsigned char> stubbedGlb;
  if (jsonText.find("EXT_meshopt_compression") != std::string::npos ||
      jsonText.find("KHR_draco_mesh_compression") != std::string::npos) {
    nlohmann::json doc = nlohmann::json::parse(jsonText, nullptr, false);
    if (gltf::prepareCompressedJson(doc)) {
      // parse() has checked the UTF-8, so replace never fires; it only keeps
      // dump() from being able to throw.
      jsonText = doc.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
      if (binary) stubbedGlb = withGlbJson(bytes, jsonText);
    }
  }
  const std::vector<unsigned char>& glb = stubbedGlb.empty() ? bytes : stubbedGlb;

  tinygltf::TinyGLTF loader;
  tinygltf::FsCallbacks callbacks{&tinygltf::FileExists, &tinygltf::ExpandFilePath,
                                  &guardedReadWholeFile, &tinygltf::WriteWholeFile,
                                  const_cast<fs::path*>(&folder)};
  loader.SetFsCallbacks(callbacks);
  loader.SetImageLoader(&tolerantImageLoader, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, glb.data(),
                                                 static_cast<unsigned int>(glb.size()),
                                                 folder.string())
                   : loader.LoadASCIIFromString(&model, &err, &warn, jsonText.c_str(),
                                                static_cast<unsigned int>(jsonText.size()),
                                                folder.string());
  for (const std::string& line : splitLines(warn)) out.warnings.push_back(path + ": " + line);
  if (!ok) {
    auto lines = splitLines(err);
    std::string message = lines.empty() ? "cannot parse glTF" : lines.front();
    for (std::size_t i = 1; i < lines.size(); ++i) message += "; " + lines[i];
    return makeError(path + ": " + message);
  }
  decodeImages(model, path, out.warnings);
  if (Status s = gltf::decodeCompressedGeometry(model, path); !s) return s.error();
  return model;
}

// KHR_materials_emissive_strength: a multiplier of emissiveFactor (1 without it),
// so that emission can pass 1 in an HDR target.
Result<float> emissiveStrength(const tinygltf::Material& material, const std::string& name) {
  auto ext = material.extensions.find("KHR_materials_emissive_strength");
  if (ext == material.extensions.end() || !ext->second.Has("emissiveStrength")) return 1.0f;
  const tinygltf::Value& value = ext->second.Get("emissiveStrength");
  const double strength = value.IsNumber() ? value.GetNumberAsDouble() : -1.0;
  if (!(strength >= 0.0) || !std::isfinite(strength) || strength > 1e30) {
    return makeError(name + ": KHR_materials_emissive_strength: emissiveStrength must be a finite number >= 0");
  }
  return static_cast<float>(strength);
}

// One number of a material extension: `fallback` when absent, an error naming the
// material, the extension and the key when it is not a number inside [lo, hi].
Result<float> extensionNumber(const tinygltf::Value& ext, const char* key, float fallback, double lo, double hi,
                              const std::string& where) {
  if (!ext.Has(key)) return fallback;
  const tinygltf::Value& value = ext.Get(key);
  const double v = value.IsNumber() ? value.GetNumberAsDouble() : std::nan("");
  if (!(v >= lo && v <= hi)) {
    char range[64];
    std::snprintf(range, sizeof range, "[%g, %g]", lo, hi);
    return makeError(where + ": " + key + " must be a number in " + range);
  }
  return static_cast<float>(v);
}

// One colour of a material extension: `fallback` when absent, an error naming the
// material, the extension and the key unless it is three numbers in [0, most].
Result<glm::vec3> extensionColor(const tinygltf::Value& ext, const char* key, float most, const std::string& where,
                                 const char* expected, glm::vec3 fallback = glm::vec3(1.0f)) {
  if (!ext.Has(key)) return fallback;
  const tinygltf::Value& c = ext.Get(key);
  const bool ok = c.IsArray() && c.ArrayLen() == 3 && c.Get(0).IsNumber() && c.Get(1).IsNumber() && c.Get(2).IsNumber();
  const glm::vec3 color = ok ? glm::vec3(c.Get(0).GetNumberAsDouble(), c.Get(1).GetNumberAsDouble(), c.Get(2).GetNumberAsDouble())
                             : glm::vec3(-1.0f);
  if (!(glm::all(glm::greaterThanEqual(color, glm::vec3(0.0f))) && glm::all(glm::lessThanEqual(color, glm::vec3(most)))))
    return makeError(where + ": " + key + " must be " + expected);
  return color;
}

// KHR_materials_volume: thickness and Beer-Lambert's attenuation.
Status readVolume(const tinygltf::Value& ext, const std::string& name, MaterialLayers& layers) {
  const std::string where = name + ": KHR_materials_volume";
  auto thickness = extensionNumber(ext, "thicknessFactor", 0.0f, 0.0, 1e30, where);
  if (!thickness) return thickness.error();
  // Absent means infinite (nothing absorbed), which MaterialLayers writes as 0.
  auto distance = extensionNumber(ext, "attenuationDistance", 0.0f, 0.0, 1e30, where);
  if (!distance) return distance.error();
  if (ext.Has("attenuationDistance") && !(*distance > 0.0f)) return makeError(where + ": attenuationDistance must be > 0");
  layers.thickness = *thickness;
  layers.attenuationDistance = *distance;
  auto color = extensionColor(ext, "attenuationColor", 1.0f, where, "three numbers in [0, 1]");
  if (!color) return color.error();
  layers.attenuationColor = *color;
  return Ok{};
}

// KHR_materials_sheen: the fibres' colour (black, none, when absent) and roughness.
Status readSheen(const tinygltf::Value& ext, const std::string& name, MaterialLayers& layers) {
  const std::string where = name + ": KHR_materials_sheen";
  auto color = extensionColor(ext, "sheenColorFactor", 1.0f, where, "three numbers in [0, 1]", glm::vec3(0.0f));
  if (!color) return color.error();
  auto roughness = extensionNumber(ext, "sheenRoughnessFactor", 0.0f, 0.0, 1.0, where);
  if (!roughness) return roughness.error();
  layers.sheenColor = *color;
  layers.sheenRoughness = *roughness;
  return Ok{};
}

// KHR_materials_anisotropy: the stretch's strength and its direction's turn.
Status readAnisotropy(const tinygltf::Value& ext, const std::string& name, MaterialLayers& layers) {
  const std::string where = name + ": KHR_materials_anisotropy";
  auto strength = extensionNumber(ext, "anisotropyStrength", 0.0f, 0.0, 1.0, where);
  if (!strength) return strength.error();
  auto rotation = extensionNumber(ext, "anisotropyRotation", 0.0f, -1e6, 1e6, where);
  if (!rotation) return rotation.error();
  layers.anisotropy = *strength;
  layers.anisotropyRotation = *rotation;
  return Ok{};
}

// KHR_materials_iridescence: the film's share, index and thickness range (nm).
Status readIridescence(const tinygltf::Value& ext, const std::string& name, MaterialLayers& layers) {
  const std::string where = name + ": KHR_materials_iridescence";
  auto factor = extensionNumber(ext, "iridescenceFactor", 0.0f, 0.0, 1.0, where);
  if (!factor) return factor.error();
  auto ior = extensionNumber(ext, "iridescenceIor", 1.3f, 1.0, 1e6, where);
  if (!ior) return ior.error();
  auto thinnest = extensionNumber(ext, "iridescenceThicknessMinimum", 100.0f, 0.0, 1e6, where);
  if (!thinnest) return thinnest.error();
  auto thickest = extensionNumber(ext, "iridescenceThicknessMaximum", 400.0f, 0.0, 1e6, where);
  if (!thickest) return thickest.error();
  layers.iridescence = *factor;
  layers.iridescenceIor = *ior;
  layers.iridescenceThicknessMin = *thinnest;
  layers.iridescenceThicknessMax = *thickest;
  return Ok{};
}

// KHR_materials_ior, _specular, _clearcoat, _transmission, _volume, _sheen,
// _anisotropy and _iridescence.
Result<MaterialLayers> materialLayers(const tinygltf::Material& material, const std::string& name) {
  MaterialLayers layers;
  auto has = [&](const char* ext) { return material.extensions.find(ext) != material.extensions.end(); };
  if (has("KHR_materials_ior")) {
    const tinygltf::Value& ext = material.extensions.at("KHR_materials_ior");
    // glTF allows 0 besides [1, inf): it reads as a perfect mirror (f0 = 1).
    auto ior = extensionNumber(ext, "ior", 1.5f, 0.0, 1e6, name + ": KHR_materials_ior");
    if (!ior) return ior.error();
    if (*ior > 0.0f && *ior < 1.0f) return makeError(name + ": KHR_materials_ior: ior must be 0 or at least 1");
    layers.ior = *ior;
  }
  if (has("KHR_materials_specular")) {
    const tinygltf::Value& ext = material.extensions.at("KHR_materials_specular");
    const std::string where = name + ": KHR_materials_specular";
    auto weight = extensionNumber(ext, "specularFactor", 1.0f, 0.0, 1.0, where);
    if (!weight) return weight.error();
    layers.specular = *weight;
    auto color = extensionColor(ext, "specularColorFactor", 1e6f, where, "three numbers >= 0");
    if (!color) return color.error();
    layers.specularColor = *color;
  }
  if (has("KHR_materials_clearcoat")) {
    const tinygltf::Value& ext = material.extensions.at("KHR_materials_clearcoat");
    const std::string where = name + ": KHR_materials_clearcoat";
    auto coat = extensionNumber(ext, "clearcoatFactor", 0.0f, 0.0, 1.0, where);
    if (!coat) return coat.error();
    auto roughness = extensionNumber(ext, "clearcoatRoughnessFactor", 0.0f, 0.0, 1.0, where);
    if (!roughness) return roughness.error();
    layers.clearcoat = *coat;
    layers.clearcoatRoughness = *roughness;
  }
  if (has("KHR_materials_transmission")) {
    auto transmission = extensionNumber(material.extensions.at("KHR_materials_transmission"), "transmissionFactor",
                                        0.0f, 0.0, 1.0, name + ": KHR_materials_transmission");
    if (!transmission) return transmission.error();
    layers.transmission = *transmission;
  }
  if (has("KHR_materials_volume")) {
    if (auto status = readVolume(material.extensions.at("KHR_materials_volume"), name, layers); !status) return status.error();
  }
  if (has("KHR_materials_sheen")) {
    if (auto status = readSheen(material.extensions.at("KHR_materials_sheen"), name, layers); !status) return status.error();
  }
  if (has("KHR_materials_anisotropy")) {
    const tinygltf::Value& ext = material.extensions.at("KHR_materials_anisotropy");
    if (auto status = readAnisotropy(ext, name, layers); !status) return status.error();
  }
  if (has("KHR_materials_iridescence")) {
    const tinygltf::Value& ext = material.extensions.at("KHR_materials_iridescence");
    if (auto status = readIridescence(ext, name, layers); !status) return status.error();
  }
  return layers;
}

class Converter {
 public:
  Converter(const tinygltf::Model& gltf, ModelData& out, int scene) : gltf_(gltf), out_(out), file_(out.path), scene_(scene) {}

  Status run() {
    if (Status s = checkLimits(); !s) return s;
    if (Status s = convertNodes(); !s) return s;
    if (Status s = convertImages(); !s) return s;
    if (Status s = convertMaterials(); !s) return s;
    if (Status s = convertMeshes(); !s) return s;
    if (Status s = convertVariants(); !s) return s;
    if (Status s = resolveNodeWeights(); !s) return s;
    if (Status s = convertSkins(); !s) return s;
    if (Status s = checkSkinnedMeshes(); !s) return s;
    if (Status s = convertInstancing(); !s) return s;
    if (Status s = convertLights(); !s) return s;
    if (Status s = convertCameras(); !s) return s;
    if (Status s = convertAnimations(); !s) return s;
    leaveOutOtherScenes();
    return Ok{};
  }

 private:
  Error error(const std::string& message) const { return makeError(file_ + ": " + message); }
  void warn(const std::string& message) { out_.warnings.push_back(file_ + ": " + message); }

  Status checkLimits() {
    if (gltf_.nodes.size() > kMaxNodes)
      return error(str(gltf_.nodes.size()) + " nodes, the limit is " + str(kMaxNodes));
    for (std::size_t i = 0; i < gltf_.skins.size(); ++i)
      if (gltf_.skins[i].joints.size() > kMaxSkinJoints)
        return error("skin " + str(i) + ": " + str(gltf_.skins[i].joints.size()) +
                     " joints, the limit is " + str(kMaxSkinJoints));
    return Ok{};
  }

  Status convertNodes() {
    std::size_t count = gltf_.nodes.size();
    out_.nodes.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      if (Status s = convertNode(i); !s) return s;
    }
    if (Status s = checkTree(); !s) return s;
    return findSceneRoots();
  }

  Status convertNode(std::size_t i) {
    const tinygltf::Node& src = gltf_.nodes[i];
    NodeData& node = out_.nodes[i];
    std::string name = "node " + str(i);
    node.name = src.name;
    if (src.mesh != -1 && !validIndex(src.mesh, gltf_.meshes.size()))
      return error(name + ": mesh " + str(src.mesh) + " does not exist");
    if (src.skin != -1 && !validIndex(src.skin, gltf_.skins.size()))
      return error(name + ": skin " + str(src.skin) + " does not exist");
    node.mesh = src.mesh;
    node.skin = src.skin;
    for (int child : src.children) {
      if (!validIndex(child, gltf_.nodes.size()))
        return error(name + ": child " + str(child) + " does not exist");
      std::size_t c = static_cast<std::size_t>(child);
      if (c == i) return error(name + ": is its own child (cycle)");
      if (out_.nodes[c].parent != -1)
        return error("node " + str(c) + " has two parents (nodes " + str(out_.nodes[c].parent) +
                     " and " + str(i) + ")");
      out_.nodes[c].parent = static_cast<int>(i);
      node.children.push_back(child);
    }
    return readNodeTransform(src, node, name);
  }

  Status readNodeTransform(const tinygltf::Node& src, NodeData& node, const std::string& name) {
    auto finite = [](const std::vector<double>& v) {
      return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
    };
    if (!finite(src.matrix) || !finite(src.translation) || !finite(src.rotation) || !finite(src.scale))
      return error(name + ": transform has a NaN or infinite value");
    if (src.matrix.size() == 16) {
      glm::mat4 m;
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) m[c][r] = static_cast<float>(src.matrix[static_cast<std::size_t>(c * 4 + r)]);
      Srt srt = decompose(m);
      node.translation = srt.translation;
      node.rotation = srt.rotation;
      node.scale = srt.scale;
      return Ok{};
    }
    if (!src.matrix.empty()) return error(name + ": matrix must have 16 numbers");
    if (src.translation.size() == 3)
      node.translation = glm::vec3(src.translation[0], src.translation[1], src.translation[2]);
    if (src.scale.size() == 3) node.scale = glm::vec3(src.scale[0], src.scale[1], src.scale[2]);
    if (src.rotation.size() == 4)
      node.rotation = safeNormalize(glm::quat(static_cast<float>(src.rotation[3]), static_cast<float>(src.rotation[0]),
                                              static_cast<float>(src.rotation[1]), static_cast<float>(src.rotation[2])));
    return Ok{};
  }

  // With at most one parent per node (checked above), a node that cannot be
  // reached from a root sits on a cycle.
  Status checkTree() {
    std::vector<char> reached(out_.nodes.size(), 0);
    std::vector<int> stack;
    for (std::size_t i = 0; i < out_.nodes.size(); ++i)
      if (out_.nodes[i].parent == -1) stack.push_back(static_cast<int>(i));
    while (!stack.empty()) {
      int n = stack.back();
      stack.pop_back();
      reached[static_cast<std::size_t>(n)] = 1;
      for (int c : out_.nodes[static_cast<std::size_t>(n)].children) stack.push_back(c);
    }
    for (std::size_t i = 0; i < reached.size(); ++i)
      if (!reached[i]) return error("node " + str(i) + ": is part of a cycle in the node tree");
    return Ok{};
  }

  // The scene drawn: the one asked for (viewer --scene), else the file's default,
  // else its first; a file without scenes (or an empty one) draws every root.
  Status findSceneRoots() {
    if (scene_ >= 0 && !validIndex(scene_, gltf_.scenes.size()))
      return error("scene " + str(scene_) + " does not exist (the file has " + str(gltf_.scenes.size()) + ")");
    const int scene = scene_ >= 0 ? scene_ : gltf_.defaultScene >= 0 ? gltf_.defaultScene : 0;
    if (validIndex(scene, gltf_.scenes.size())) {
      for (int n : gltf_.scenes[static_cast<std::size_t>(scene)].nodes)
        if (validIndex(n, out_.nodes.size()) && out_.nodes[static_cast<std::size_t>(n)].parent == -1)
          out_.sceneRoots.push_back(n);
      if (!out_.sceneRoots.empty()) {
        out_.scene = scene;
        return Ok{};
      }
    }
    for (std::size_t i = 0; i < out_.nodes.size(); ++i)
      if (out_.nodes[i].parent == -1) out_.sceneRoots.push_back(static_cast<int>(i));
    return Ok{};
  }

  // Nodes outside the scene drawn keep their place in the tree and their animation,
  // but draw, light and look through nothing (MultipleScenes' other scene's mesh
  // would otherwise lie in this one's).
  void leaveOutOtherScenes() {
    if (out_.scene < 0) return;
    std::vector<char> inScene(out_.nodes.size(), 0);
    std::vector<int> stack(out_.sceneRoots.begin(), out_.sceneRoots.end());
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      inScene[static_cast<std::size_t>(n)] = 1;
      for (int c : out_.nodes[static_cast<std::size_t>(n)].children) stack.push_back(c);
    }
    for (std::size_t i = 0; i < out_.nodes.size(); ++i) {
      if (inScene[i]) continue;
      NodeData& node = out_.nodes[i];
      node.mesh = -1;
      node.instances.clear();
      node.light = -1;
      node.camera = -1;
    }
  }

  Status convertImages() {
    for (std::size_t i = 0; i < gltf_.images.size(); ++i) {
      const tinygltf::Image& src = gltf_.images[i];
      ImageData image;
      image.name = src.name;
      if (src.uri.rfind("data:", 0) != 0) image.uri = src.uri;
      if (!toRgba8(src, image.image)) {
        warn("image " + str(i) + " (" + (src.uri.empty() ? src.name : src.uri) +
             "): missing or undecodable, using a white 1x1 fallback");
        image.missing = true;
        image.image = Image(1, 1);
        std::fill(image.image.pixels.begin(), image.image.pixels.end(), std::uint8_t{255});
      }
      out_.images.push_back(std::move(image));
    }
    return Ok{};
  }

  static bool toRgba8(const tinygltf::Image& src, Image& dst) {
    if (src.width <= 0 || src.height <= 0 || src.component < 1 || src.component > 4) return false;
    std::size_t pixels = static_cast<std::size_t>(src.width) * static_cast<std::size_t>(src.height);
    std::size_t bytesPerChannel = src.bits == 16 ? 2 : 1;
    if (src.bits != 8 && src.bits != 16) return false;
    if (src.image.size() < pixels * static_cast<std::size_t>(src.component) * bytesPerChannel) return false;
    dst = Image(src.width, src.height);
    if (src.component == 4 && bytesPerChannel == 1) {  // what tinygltf decodes to: as it is
      std::memcpy(dst.pixels.data(), src.image.data(), pixels * 4);
      return true;
    }
    for (std::size_t p = 0; p < pixels; ++p) {
      std::uint8_t rgba[4] = {0, 0, 0, 255};
      for (int c = 0; c < src.component; ++c) {
        std::size_t at = (p * static_cast<std::size_t>(src.component) + static_cast<std::size_t>(c)) * bytesPerChannel;
        // 16-bit samples are little-endian as stb returns them; keep the high byte.
        rgba[c] = bytesPerChannel == 2 ? src.image[at + 1] : src.image[at];
      }
      // Grey and grey+alpha images spread the grey over RGB.
      if (src.component <= 2) {
        std::uint8_t alpha = src.component == 2 ? rgba[1] : std::uint8_t{255};
        rgba[1] = rgba[2] = rgba[0];
        rgba[3] = alpha;
      }
      std::memcpy(&dst.pixels[p * 4], rgba, 4);
    }
    return true;
  }

  // The image behind a material's texture slot, or -1, and how the slot samples
  // it (`slot`: uv set, KHR_texture_transform, sampler). A texture index or source
  // out of range is a warning naming the material and the slot, and the slot is
  // left empty; a uv set other than 0 and 1, a malformed transform or sampler a
  // warning, and the default is used in its place.
  template <typename Info>
  int textureImage(const Info& info, const std::string& material, const char* slotName, TextureSlotData& slot) {
    if (info.index < 0) return -1;
    const std::string where = material + ": " + slotName + " " + str(info.index);
    if (!validIndex(info.index, gltf_.textures.size())) {
      warn(where + " does not exist; drawn without it");
      return -1;
    }
    const tinygltf::Texture& texture = gltf_.textures[static_cast<std::size_t>(info.index)];
    const int source = texture.source;
    if (!validIndex(source, out_.images.size())) {
      warn(where + ": image " + str(source) + " does not exist; drawn without it");
      return -1;
    }
    int texCoord = info.texCoord;
    if (auto ext = info.extensions.find("KHR_texture_transform"); ext != info.extensions.end())
      readTextureTransform(ext->second, where + ": KHR_texture_transform", slot, texCoord);
    if (texCoord != 0 && texCoord != 1) {
      warn(where + ": TEXCOORD_" + str(texCoord) + " is not supported (TEXCOORD_0 and TEXCOORD_1 are); TEXCOORD_0 is used");
      texCoord = 0;
    }
    slot.texCoord = texCoord;
    if (texture.sampler >= 0) slot.sampler = readSampler(texture.sampler, where);
    return source;
  }

  // A textureInfo inside a material extension, which tinygltf leaves as JSON.
  struct ExtensionTextureInfo {
    int index = -1;
    int texCoord = 0;
    tinygltf::ExtensionMap extensions;
  };
  static ExtensionTextureInfo extensionTextureInfo(const tinygltf::Value& v) {
    ExtensionTextureInfo info;
    if (!v.IsObject()) return info;
    if (v.Has("index") && v.Get("index").IsNumber()) info.index = v.Get("index").GetNumberAsInt();
    if (v.Has("texCoord") && v.Get("texCoord").IsNumber()) info.texCoord = v.Get("texCoord").GetNumberAsInt();
    if (v.Has("extensions") && v.Get("extensions").IsObject()) {
      const tinygltf::Value& ext = v.Get("extensions");
      for (const std::string& key : ext.Keys()) info.extensions[key] = ext.Get(key);
    }
    return info;
  }

  // The textures of KHR_materials_specular, _clearcoat (its normal map too),
  // _transmission, _volume, _sheen, _anisotropy and _iridescence, each with its uv set, transform and sampler as the
  // core slots have them.
  void readLayerTextures(const tinygltf::Material& src, const std::string& name, MaterialData& m) {
    struct Key {
      const char* extension;
      const char* key;
      TextureSlot slot;
    };
    static const Key kKeys[] = {{"KHR_materials_specular", "specularTexture", TextureSlot::Specular},
                                {"KHR_materials_specular", "specularColorTexture", TextureSlot::SpecularColor},
                                {"KHR_materials_clearcoat", "clearcoatTexture", TextureSlot::Clearcoat},
                                {"KHR_materials_clearcoat", "clearcoatRoughnessTexture", TextureSlot::ClearcoatRoughness},
                                {"KHR_materials_transmission", "transmissionTexture", TextureSlot::Transmission},
                                {"KHR_materials_volume", "thicknessTexture", TextureSlot::Thickness},
                                {"KHR_materials_clearcoat", "clearcoatNormalTexture", TextureSlot::ClearcoatNormal},
                                {"KHR_materials_sheen", "sheenColorTexture", TextureSlot::SheenColor},
                                {"KHR_materials_sheen", "sheenRoughnessTexture", TextureSlot::SheenRoughness},
                                {"KHR_materials_anisotropy", "anisotropyTexture", TextureSlot::Anisotropy},
                                {"KHR_materials_iridescence", "iridescenceTexture", TextureSlot::Iridescence},
                                {"KHR_materials_iridescence", "iridescenceThicknessTexture",
                                 TextureSlot::IridescenceThickness}};
    for (const Key& k : kKeys) {
      auto ext = src.extensions.find(k.extension);
      if (ext == src.extensions.end() || !ext->second.Has(k.key)) continue;
      const ExtensionTextureInfo info = extensionTextureInfo(ext->second.Get(k.key));
      if (info.index < 0) {
        warn(name + ": " + k.extension + ": " + k.key + " has no texture index; drawn without it");
        continue;
      }
      const std::string slotName = std::string(k.extension) + ": " + k.key;
      m.layerImages[std::size_t(k.slot) - kFirstLayerSlot] = textureImage(info, name, slotName.c_str(), m.texture(k.slot));
      if (k.slot == TextureSlot::ClearcoatNormal) m.layers.clearcoatNormalScale = normalScale(ext->second.Get(k.key));
    }
  }

  // A normal map's textureInfo "scale" (1 when absent or not a finite number).
  static float normalScale(const tinygltf::Value& info) {
    if (!info.Has("scale") || !info.Get("scale").IsNumber()) return 1.0f;
    const double scale = info.Get("scale").GetNumberAsDouble();
    return std::isfinite(scale) && std::abs(scale) < 1e6 ? float(scale) : 1.0f;
  }

  // KHR_texture_transform on one textureInfo: offset, rotation, scale (each
  // defaulted when absent or malformed, with a warning for the latter) and the
  // texCoord that overrides the textureInfo's.
  void readTextureTransform(const tinygltf::Value& ext, const std::string& where, TextureSlotData& slot,
                            int& texCoord) {
    auto number = [&](const tinygltf::Value& v, double& out) {
      if (!v.IsNumber()) return false;
      out = v.GetNumberAsDouble();
      return std::isfinite(out) && std::abs(out) < 1e30;
    };
    auto vec2 = [&](const char* key, glm::vec2 fallback) {
      if (!ext.Has(key)) return fallback;
      const tinygltf::Value& v = ext.Get(key);
      double x = 0.0, y = 0.0;
      if (!v.IsArray() || v.ArrayLen() != 2 || !number(v.Get(0), x) || !number(v.Get(1), y)) {
        warn(where + ": " + key + " must be 2 finite numbers; [" + (fallback.x == 0.0f ? "0, 0" : "1, 1") +
             "] is used");
        return fallback;
      }
      return glm::vec2(float(x), float(y));
    };
    const glm::vec2 offset = vec2("offset", glm::vec2(0.0f));
    const glm::vec2 scale = vec2("scale", glm::vec2(1.0f));
    double rotation = 0.0;
    if (ext.Has("rotation") && !number(ext.Get("rotation"), rotation)) {
      warn(where + ": rotation must be a finite number; 0 is used");
      rotation = 0.0;
    }
    if (ext.Has("texCoord")) {
      const tinygltf::Value& v = ext.Get("texCoord");
      if (v.IsInt() && v.GetNumberAsInt() >= 0) texCoord = v.GetNumberAsInt();
      else warn(where + ": texCoord must be an integer >= 0; the textureInfo's TEXCOORD_" + str(texCoord) + " is used");
    }
    slot.uvTransform = textureTransformMatrix(offset, float(rotation), scale);
  }

  // A glTF sampler's wrap modes and filters; an unknown value (or a sampler that
  // does not exist) is a warning and glTF's default in its place.
  SamplerData readSampler(int index, const std::string& where) {
    SamplerData out;
    if (!validIndex(index, gltf_.samplers.size())) {
      warn(where + ": sampler " + str(index) + " does not exist; repeat and trilinear are used");
      return out;
    }
    const tinygltf::Sampler& s = gltf_.samplers[static_cast<std::size_t>(index)];
    const std::string name = where + ": sampler " + str(index);
    auto wrap = [&](int value, const char* key) {
      if (value == 10497 || value == 33071 || value == 33648) return static_cast<TextureWrap>(value);
      warn(name + ": " + key + " " + str(value) + " is not a wrap mode; REPEAT is used");
      return TextureWrap::Repeat;
    };
    out.wrapS = wrap(s.wrapS, "wrapS");
    out.wrapT = wrap(s.wrapT, "wrapT");
    if (s.magFilter == 9728 || s.magFilter == 9729) out.magFilter = static_cast<TextureFilter>(s.magFilter);
    else if (s.magFilter != -1) warn(name + ": magFilter " + str(s.magFilter) + " is not NEAREST or LINEAR; LINEAR is used");
    if (s.minFilter == 9728 || s.minFilter == 9729 || (s.minFilter >= 9984 && s.minFilter <= 9987))
      out.minFilter = static_cast<TextureFilter>(s.minFilter);
    else if (s.minFilter != -1)
      warn(name + ": minFilter " + str(s.minFilter) + " is not a glTF filter; LINEAR_MIPMAP_LINEAR is used");
    return out;
  }

  std::string imageName(int image) const {
    const ImageData& data = out_.images[static_cast<std::size_t>(image)];
    return "image " + str(image) + (data.uri.empty() ? "" : " (" + data.uri + ")");
  }

  Status convertMaterials() {
    for (std::size_t i = 0; i < gltf_.materials.size(); ++i) {
      const tinygltf::Material& src = gltf_.materials[i];
      const std::string name = labelled("material", i, src.name);
      MaterialData m;
      m.name = src.name;
      const auto& pbr = src.pbrMetallicRoughness;
      if (pbr.baseColorFactor.size() == 4)
        m.baseColorFactor = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1],
                                      pbr.baseColorFactor[2], pbr.baseColorFactor[3]);
      m.baseColorImage = textureImage(pbr.baseColorTexture, name, "baseColorTexture", m.texture(TextureSlot::BaseColor));
      m.metallicFactor = static_cast<float>(pbr.metallicFactor);
      m.roughnessFactor = static_cast<float>(pbr.roughnessFactor);
      m.metallicRoughnessImage = textureImage(pbr.metallicRoughnessTexture, name, "metallicRoughnessTexture", m.texture(TextureSlot::MetallicRoughness));
      m.normalImage = textureImage(src.normalTexture, name, "normalTexture", m.texture(TextureSlot::Normal));
      m.normalScale = static_cast<float>(src.normalTexture.scale);
      // A missing image becomes white (see convertImages), which is neutral for
      // every slot but the normal map, where it would tilt every normal: there the
      // fallback is the mesh's own normals.
      if (m.normalImage >= 0 && out_.images[static_cast<std::size_t>(m.normalImage)].missing) {
        warn(name + ": normalTexture " + imageName(m.normalImage) + " is missing; drawn with the mesh normals");
        m.normalImage = -1;
      }
      m.occlusionImage = textureImage(src.occlusionTexture, name, "occlusionTexture", m.texture(TextureSlot::Occlusion));
      m.occlusionStrength = static_cast<float>(src.occlusionTexture.strength);
      m.emissiveImage = textureImage(src.emissiveTexture, name, "emissiveTexture", m.texture(TextureSlot::Emissive));
      if (src.emissiveFactor.size() == 3)
        m.emissiveFactor = glm::vec3(src.emissiveFactor[0], src.emissiveFactor[1], src.emissiveFactor[2]);
      auto strength = emissiveStrength(src, name);
      if (!strength) return error(strength.error().message);
      m.emissiveFactor *= *strength;
      m.doubleSided = src.doubleSided;
      m.unlit = src.extensions.count("KHR_materials_unlit") > 0;
      auto layers = materialLayers(src, name);
      if (!layers) return error(layers.error().message);
      m.layers = *layers;
      readLayerTextures(src, name, m);
      m.alphaMode = src.alphaMode == "BLEND" ? AlphaMode::Blend : src.alphaMode == "MASK" ? AlphaMode::Mask : AlphaMode::Opaque;
      m.alphaCutoff = static_cast<float>(src.alphaCutoff);
      const bool finite = std::isfinite(m.normalScale) && std::isfinite(m.occlusionStrength) &&
                          std::isfinite(m.alphaCutoff) && std::isfinite(m.metallicFactor) &&
                          std::isfinite(m.roughnessFactor) && std::isfinite(m.baseColorFactor.x + m.baseColorFactor.y +
                                                                            m.baseColorFactor.z + m.baseColorFactor.w) &&
                          std::isfinite(m.emissiveFactor.x + m.emissiveFactor.y + m.emissiveFactor.z);
      if (!finite) return error(name + ": a factor is NaN or infinite");
      out_.materials.push_back(std::move(m));
    }
    return Ok{};
  }

  // Normal maps and anisotropy need tangents: primitives without TANGENT get
  // generated ones, as glTF asks; without NORMAL or TEXCOORD_0 there is nothing to
  // build them from, and the primitive is drawn without its normal map (or stretch).
  void addMissingTangents(PrimitiveData& prim, const std::string& name) {
    if (prim.material < 0 || !prim.tangents.empty()) return;
    const MaterialData& material = out_.materials[static_cast<std::size_t>(prim.material)];
    const TextureSlot slot = material.normalImage >= 0                                ? TextureSlot::Normal
                             : material.image(TextureSlot::ClearcoatNormal) >= 0     ? TextureSlot::ClearcoatNormal
                             : material.image(TextureSlot::Anisotropy) >= 0          ? TextureSlot::Anisotropy
                                                                                      : TextureSlot::BaseColor;
    if (slot == TextureSlot::BaseColor && material.layers.anisotropy <= 0.0f) return;
    const bool set1 = material.texture(slot).texCoord == 1;
    const std::vector<glm::vec2>& uvs = set1 ? prim.uvs1 : prim.uvs;
    if (prim.normals.empty() || uvs.empty() || prim.mode != 4) {
      const char* what = slot == TextureSlot::Normal || slot == TextureSlot::ClearcoatNormal ? "a normal map" : "anisotropy";
      warn(name + ": " + what + " needs NORMAL, TEXCOORD_" + (set1 ? "1" : "0") +
           " and triangles to build tangents; drawn without it");
      return;
    }
    prim.tangents = generateTangents(prim.positions, prim.normals, uvs, prim.indices);
  }

  // A material texture that reads TEXCOORD_1 on a primitive without it: a warning
  // naming the primitive, the material and the slot, and set 0 is read instead
  // (copied into uvs1, so that every renderer finds the set it asks for).
  void checkUvSets(PrimitiveData& prim, const std::string& name) {
    if (prim.material < 0 || !prim.uvs1.empty()) return;
    const MaterialData& m = out_.materials[static_cast<std::size_t>(prim.material)];
    const std::string material = "material " + str(prim.material) + (m.name.empty() ? "" : " (\"" + m.name + "\")");
    bool needed = false;
    for (int i = 0; i < kTextureSlots; ++i) {
      if (m.image(TextureSlot(i)) < 0 || m.textures[std::size_t(i)].texCoord != 1) continue;
      warn(name + ": " + material + ": " + textureSlotName(TextureSlot(i)) + " reads TEXCOORD_1, which the primitive does not have; TEXCOORD_0 is used");
      needed = true;
    }
    if (needed) prim.uvs1 = prim.uvs;
  }

  // Reads an attribute that must have `components` per element and `count`
  // elements (0 = any), as floats.
  Result<std::vector<float>> readFloats(int accessor, int components, std::size_t count,
                                        const std::string& context) {
    auto values = readAccessor(gltf_, accessor, file_ + ": " + context);
    if (!values) return values.error();
    if (values->components != components)
      return error(context + ": expected " + str(components) + " components per element, got " +
                   str(values->components));
    if (count != 0 && values->count != count)
      return error(context + ": has " + str(values->count) + " elements, expected " + str(count));
    std::vector<float> out(values->values.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
      out[i] = static_cast<float>(values->values[i]);
      if (!std::isfinite(out[i])) return error(context + ": element " + str(i / static_cast<std::size_t>(components)) + " is NaN or infinite");
    }
    return out;
  }

  template <typename Vec>
  static std::vector<Vec> toVectors(const std::vector<float>& flat) {
    constexpr int n = Vec::length();
    std::vector<Vec> out(flat.size() / n);
    for (std::size_t i = 0; i < out.size(); ++i)
      for (int c = 0; c < n; ++c) out[i][c] = flat[i * n + static_cast<std::size_t>(c)];
    return out;
  }

  Status convertMeshes() {
    for (std::size_t m = 0; m < gltf_.meshes.size(); ++m) {
      MeshData mesh;
      mesh.name = gltf_.meshes[m].name;
      for (std::size_t p = 0; p < gltf_.meshes[m].primitives.size(); ++p) {
        PrimitiveData prim;
        std::string name = "mesh " + str(m) + " primitive " + str(p);
        if (Status s = convertPrimitive(gltf_.meshes[m].primitives[p], prim, name); !s) return s;
        mesh.primitives.push_back(std::move(prim));
      }
      if (Status s = readMeshWeights(gltf_.meshes[m], mesh, "mesh " + str(m)); !s) return s;
      out_.meshes.push_back(std::move(mesh));
    }
    return Ok{};
  }

  static int targetCount(const MeshData& mesh) {
    return mesh.primitives.empty() ? 0 : mesh.primitives.front().morphTargets;
  }

  // glTF requires the same number of targets in every primitive of a mesh, since
  // one list of weights drives them all; `weights`, when given, has one per target.
  Status readMeshWeights(const tinygltf::Mesh& src, MeshData& mesh, const std::string& name) {
    const int targets = targetCount(mesh);
    for (std::size_t p = 1; p < mesh.primitives.size(); ++p)
      if (mesh.primitives[p].morphTargets != targets)
        return error(name + ": primitive " + str(p) + " has " + str(mesh.primitives[p].morphTargets) +
                     " morph targets, primitive 0 has " + str(targets) + " (every primitive needs the same number)");
    auto weights = readWeightList(src.weights, targets, name);
    if (!weights) return weights.error();
    mesh.morphWeights = std::move(weights).value();
    return Ok{};
  }

  // KHR_materials_variants (asset/material_variants.h). A primitive drawn with a
  // variant's material gets what that material needs too: tangents for its normal
  // map, TEXCOORD_1 (or set 0 in its place) for its textures.
  Status convertVariants() {
    if (Status s = readMaterialVariants(gltf_, file_, out_); !s) return s;
    for (std::size_t m = 0; m < out_.meshes.size(); ++m) {
      for (std::size_t p = 0; p < out_.meshes[m].primitives.size(); ++p) {
        PrimitiveData& prim = out_.meshes[m].primitives[p];
        const int own = prim.material;
        for (const int material : prim.variantMaterials) {
          if (material < 0 || material == own) continue;
          prim.material = material;
          const std::string name = "mesh " + str(m) + " primitive " + str(p);
          checkUvSets(prim, name);
          addMissingTangents(prim, name);
        }
        prim.material = own;
      }
    }
    return Ok{};
  }

  // The file's cameras, then the node of each that places it.
  Status convertCameras() {
    for (std::size_t i = 0; i < gltf_.cameras.size(); ++i) {
      auto camera = convertCamera(gltf_.cameras[i], labelled("camera", i, gltf_.cameras[i].name));
      if (!camera) return camera.error();
      out_.cameras.push_back(std::move(camera).value());
    }
    for (std::size_t n = 0; n < out_.nodes.size(); ++n) {
      const int camera = gltf_.nodes[n].camera;
      if (camera == -1) continue;
      if (!validIndex(camera, out_.cameras.size()))
        return error("node " + str(n) + ": camera " + str(camera) + " does not exist (" + str(out_.cameras.size()) + " cameras)");
      out_.nodes[n].camera = camera;
    }
    return Ok{};
  }

  // One camera; an error names it and the value out of glTF's range.
  Result<CameraData> convertCamera(const tinygltf::Camera& src, const std::string& where) {
    CameraData camera;
    camera.name = src.name;
    camera.perspective = src.type == "perspective";
    if (!camera.perspective && src.type != "orthographic")
      return error(where + ": type \"" + src.type + "\" is not perspective or orthographic");
    if (camera.perspective) {
      const tinygltf::PerspectiveCamera& p = src.perspective;
      if (!(p.yfov > 0.0 && p.yfov < 3.14159265358979)) return error(where + ": yfov must be in (0, pi)");
      if (!(p.znear > 0.0 && std::isfinite(p.znear))) return error(where + ": znear must be > 0");
      if (!(p.zfar == 0.0 || (p.zfar > p.znear && std::isfinite(p.zfar)))) return error(where + ": zfar must be > znear");
      if (!(p.aspectRatio >= 0.0 && std::isfinite(p.aspectRatio))) return error(where + ": aspectRatio must be > 0");
      camera.yfov = float(p.yfov);
      camera.znear = float(p.znear);
      camera.zfar = float(p.zfar);
      camera.aspectRatio = float(p.aspectRatio);
      return camera;
    }
    const tinygltf::OrthographicCamera& o = src.orthographic;
    if (!(o.xmag != 0.0 && o.ymag != 0.0 && std::isfinite(o.xmag) && std::isfinite(o.ymag)))
      return error(where + ": xmag and ymag must be finite and not 0");
    if (!(o.znear >= 0.0 && o.zfar > o.znear && std::isfinite(o.zfar))) return error(where + ": needs 0 <= znear < zfar");
    camera.xmag = float(o.xmag);
    camera.ymag = float(o.ymag);
    camera.znear = float(o.znear);
    camera.zfar = float(o.zfar);
    return camera;
  }

  // KHR_lights_punctual: the file's lights (tinygltf parses the list), then the
  // node of each that places it.
  Status convertLights() {
    for (std::size_t i = 0; i < gltf_.lights.size(); ++i) {
      auto light = convertLight(gltf_.lights[i], labelled("light", i, gltf_.lights[i].name));
      if (!light) return light.error();
      out_.lights.push_back(std::move(light).value());
    }
    for (std::size_t n = 0; n < out_.nodes.size(); ++n) {
      auto ext = gltf_.nodes[n].extensions.find("KHR_lights_punctual");
      if (ext == gltf_.nodes[n].extensions.end()) continue;
      const std::string where = "node " + str(n) + ": KHR_lights_punctual";
      if (!ext->second.IsObject() || !ext->second.Has("light") || !ext->second.Get("light").IsInt())
        return error(where + ": needs a \"light\" index");
      const int light = ext->second.Get("light").GetNumberAsInt();
      if (!validIndex(light, out_.lights.size()))
        return error(where + ": light " + str(light) + " does not exist (" + str(out_.lights.size()) + " lights)");
      out_.nodes[n].light = light;
    }
    return Ok{};
  }

  Result<PunctualLightData> convertLight(const tinygltf::Light& src, const std::string& where) {
    PunctualLightData light;
    light.name = src.name;
    if (src.type == "directional") light.type = PunctualType::Directional;
    else if (src.type == "point") light.type = PunctualType::Point;
    else if (src.type == "spot") light.type = PunctualType::Spot;
    else return error(where + ": type \"" + src.type + "\" is not directional, point or spot");
    if (!src.color.empty()) {
      if (src.color.size() != 3) return error(where + ": color must have 3 numbers");
      for (int c = 0; c < 3; ++c) {
        const double v = src.color[std::size_t(c)];
        if (!std::isfinite(v) || v < 0.0) return error(where + ": color must be finite and >= 0");
        light.color[c] = float(v);
      }
    }
    if (!std::isfinite(src.intensity) || src.intensity < 0.0 || src.intensity > 1e30)
      return error(where + ": intensity must be a finite number >= 0");
    light.intensity = float(src.intensity);
    if (!std::isfinite(src.range) || src.range < 0.0) return error(where + ": range must be a finite number >= 0");
    light.range = float(src.range);
    if (light.type == PunctualType::Spot) {
      light.innerConeAngle = float(src.spot.innerConeAngle);
      light.outerConeAngle = float(src.spot.outerConeAngle);
      // The engine's lights have no cone: the light reaches every direction.
      warn(where + ": a spot light; drawn as a point light, without its cone");
    }
    return light;
  }

  // EXT_mesh_gpu_instancing on every node that has it.
  Status convertInstancing() {
    for (std::size_t n = 0; n < out_.nodes.size(); ++n) {
      auto ext = gltf_.nodes[n].extensions.find("EXT_mesh_gpu_instancing");
      if (ext == gltf_.nodes[n].extensions.end()) continue;
      if (Status s = readInstancing(ext->second, n); !s) return s;
    }
    return Ok{};
  }

  // One instancing attribute (TRANSLATION, ROTATION or SCALE): `components` floats
  // per instance, or nothing when the node does not give it. The count is checked
  // against the other attributes' by the caller.
  Result<std::optional<AccessorValues>> instancingAttribute(const tinygltf::Value& attributes, const char* semantic,
                                                            int components, const std::string& where) const {
    if (!attributes.Has(semantic)) return std::optional<AccessorValues>{};
    const tinygltf::Value& id = attributes.Get(semantic);
    const std::string name = where + " " + semantic;
    if (!id.IsInt()) return error(name + ": must be an accessor index");
    // The instance limit before the values are read: a large sparse accessor costs
    // nothing in the file but 32 bytes per component once read.
    const int index = id.GetNumberAsInt();
    if (validIndex(index, gltf_.accessors.size()) && gltf_.accessors[std::size_t(index)].count > kMaxNodeInstances)
      return error(name + ": accessor " + str(index) + ": " + str(gltf_.accessors[std::size_t(index)].count) +
                   " instances, the limit is " + str(kMaxNodeInstances));
    auto values = readAccessor(gltf_, index, file_ + ": " + name);
    if (!values) return values.error();
    if (values->components != components)
      return error(name + ": accessor " + str(id.GetNumberAsInt()) + " has " + str(values->components) +
                   " components per element, expected " + str(components) + (components == 3 ? " (VEC3)" : " (VEC4)"));
    for (double v : values->values)
      if (!std::isfinite(v)) return error(name + ": accessor " + str(id.GetNumberAsInt()) + " has a NaN or infinite value");
    return std::optional<AccessorValues>(std::move(values).value());
  }

  // The node's instances: every attribute that is present must have the same count
  // (the extension's rule); a missing one is the identity for that part.
  Status readInstancing(const tinygltf::Value& ext, std::size_t n) {
    const std::string where = "node " + str(n) + ": EXT_mesh_gpu_instancing";
    if (!ext.IsObject() || !ext.Has("attributes") || !ext.Get("attributes").IsObject())
      return error(where + ": needs an \"attributes\" object");
    const tinygltf::Value& attributes = ext.Get("attributes");
    std::optional<AccessorValues> parts[3];
    const char* semantics[3] = {"TRANSLATION", "ROTATION", "SCALE"};
    const int components[3] = {3, 4, 3};
    std::size_t count = 0;
    for (int k = 0; k < 3; ++k) {
      auto part = instancingAttribute(attributes, semantics[k], components[k], where);
      if (!part) return part.error();
      parts[k] = std::move(part).value();
      if (!parts[k]) continue;
      if (count != 0 && parts[k]->count != count)
        return error(where + " " + semantics[k] + ": has " + str(parts[k]->count) + " instances, the other attributes " +
                     str(count));
      count = parts[k]->count;
    }
    if (count == 0) return error(where + ": has no TRANSLATION, ROTATION or SCALE accessor");
    NodeData& node = out_.nodes[n];
    if (node.mesh < 0) {
      warn(where + ": the node has no mesh; ignored");
      return Ok{};
    }
    if (node.skin >= 0) {
      // A skinned mesh is placed by its joints, not its node, so instance transforms
      // relative to the node have nothing to move; drawn once, skinned.
      warn(where + ": the node is skinned; drawn once, without its instances");
      return Ok{};
    }
    node.instances.reserve(count);
    for (std::size_t i = 0; i < count; ++i) node.instances.push_back(instanceMatrix(parts, i));
    return Ok{};
  }

  static glm::mat4 instanceMatrix(const std::optional<AccessorValues> (&parts)[3], std::size_t i) {
    Srt srt;
    if (parts[0]) srt.translation = glm::vec3(float(parts[0]->at(i, 0)), float(parts[0]->at(i, 1)), float(parts[0]->at(i, 2)));
    if (parts[1])  // glTF x, y, z, w; glm's constructor takes w first
      srt.rotation = safeNormalize(glm::quat(float(parts[1]->at(i, 3)), float(parts[1]->at(i, 0)),
                                             float(parts[1]->at(i, 1)), float(parts[1]->at(i, 2))));
    if (parts[2]) srt.scale = glm::vec3(float(parts[2]->at(i, 0)), float(parts[2]->at(i, 1)), float(parts[2]->at(i, 2)));
    return toMatrix(srt);
  }

  // A mesh's or node's `weights`: one finite number per morph target; an absent
  // list is all zeros.
  Result<std::vector<float>> readWeightList(const std::vector<double>& src, int targets, const std::string& name) const {
    if (src.empty()) return std::vector<float>(static_cast<std::size_t>(targets), 0.0f);
    if (src.size() != static_cast<std::size_t>(targets))
      return error(name + ": weights has " + str(src.size()) + " entries for " + str(targets) + " morph targets");
    std::vector<float> out;
    for (std::size_t i = 0; i < src.size(); ++i) {
      if (!std::isfinite(src[i])) return error(name + ": weights entry " + str(i) + " is NaN or infinite");
      out.push_back(static_cast<float>(src[i]));
    }
    return out;
  }

  // Each node's default weights: its own (checked against its mesh), else the mesh's.
  Status resolveNodeWeights() {
    for (std::size_t n = 0; n < out_.nodes.size(); ++n) {
      NodeData& node = out_.nodes[n];
      const std::vector<double>& own = gltf_.nodes[n].weights;
      const std::string name = "node " + str(n);
      if (node.mesh < 0) {
        if (!own.empty()) return error(name + ": has weights but no mesh");
        continue;
      }
      const MeshData& mesh = out_.meshes[static_cast<std::size_t>(node.mesh)];
      if (own.empty()) {
        node.morphWeights = mesh.morphWeights;
        continue;
      }
      auto weights = readWeightList(own, targetCount(mesh), name + " (mesh " + str(node.mesh) + ")");
      if (!weights) return weights.error();
      node.morphWeights = std::move(weights).value();
    }
    return Ok{};
  }

  static int attribute(const tinygltf::Primitive& src, const char* name) {
    auto it = src.attributes.find(name);
    return it == src.attributes.end() ? -1 : it->second;
  }

  Status convertPrimitive(const tinygltf::Primitive& src, PrimitiveData& prim, const std::string& name) {
    int position = attribute(src, "POSITION");
    if (position < 0) return error(name + ": has no POSITION");
    auto positions = readFloats(position, 3, 0, name + " POSITION");
    if (!positions) return positions.error();
    prim.positions = toVectors<glm::vec3>(*positions);
    std::size_t count = prim.positions.size();
    if (int a = attribute(src, "NORMAL"); a >= 0) {
      auto v = readFloats(a, 3, count, name + " NORMAL");
      if (!v) return v.error();
      prim.normals = toVectors<glm::vec3>(*v);
    }
    if (int a = attribute(src, "TEXCOORD_0"); a >= 0) {
      auto v = readFloats(a, 2, count, name + " TEXCOORD_0");
      if (!v) return v.error();
      prim.uvs = toVectors<glm::vec2>(*v);
    }
    if (int a = attribute(src, "TEXCOORD_1"); a >= 0) {
      auto v = readFloats(a, 2, count, name + " TEXCOORD_1");
      if (!v) return v.error();
      prim.uvs1 = toVectors<glm::vec2>(*v);
    }
    if (Status s = readVertexColors(src, prim, name); !s) return s;
    if (int a = attribute(src, "TANGENT"); a >= 0) {
      auto v = readFloats(a, 4, count, name + " TANGENT");
      if (!v) return v.error();
      prim.tangents = toVectors<glm::vec4>(*v);
    }
    if (Status s = readMorphTargets(src, prim, name); !s) return s;
    if (src.material != -1 && !validIndex(src.material, out_.materials.size()))
      return error(name + ": material " + str(src.material) + " does not exist");
    prim.material = src.material;
    prim.mode = src.mode < 0 ? 4 : src.mode;
    if (Status s = readIndices(src, prim, name); !s) return s;
    checkUvSets(prim, name);
    addMissingTangents(prim, name);
    return readSkinAttributes(src, prim, name);
  }

  // COLOR_0: VEC3 or VEC4, float or normalized unsigned byte/short (readAccessor
  // maps those to 0..1), one per vertex. RGB gets alpha 1. Sets past COLOR_0 are
  // for the application, as glTF says, and are not read.
  Status readVertexColors(const tinygltf::Primitive& src, PrimitiveData& prim, const std::string& name) {
    const int a = attribute(src, "COLOR_0");
    if (a < 0) return Ok{};
    const std::string where = name + " COLOR_0";
    if (!validIndex(a, gltf_.accessors.size())) return error(where + ": accessor " + str(a) + " does not exist");
    const int type = gltf_.accessors[static_cast<std::size_t>(a)].type;
    if (type != TINYGLTF_TYPE_VEC3 && type != TINYGLTF_TYPE_VEC4) return error(where + ": must be VEC3 or VEC4");
    const int components = type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
    auto v = readFloats(a, components, prim.positions.size(), where);
    if (!v) return v.error();
    prim.colors.resize(prim.positions.size());
    for (std::size_t i = 0; i < prim.colors.size(); ++i) {
      const float* c = v->data() + i * static_cast<std::size_t>(components);
      prim.colors[i] = glm::vec4(c[0], c[1], c[2], components == 4 ? c[3] : 1.0f);
    }
    return Ok{};
  }

  // The displacements of POSITION, NORMAL and TANGENT (glTF morphs no others;
  // TEXCOORD_n and COLOR_n targets are warned about and ignored), each VEC3 with
  // one element per vertex. Read before tangents are generated: a target may only
  // move an attribute the file itself gives.
  Status readMorphTargets(const tinygltf::Primitive& src, PrimitiveData& prim, const std::string& name) {
    if (src.targets.empty()) return Ok{};
    const std::size_t count = prim.positions.size();
    const std::size_t targets = src.targets.size();
    if (targets * count > kMaxMorphDeltas)
      return error(name + ": " + str(targets) + " morph targets of " + str(count) + " vertices, the limit is " +
                   str(kMaxMorphDeltas) + " displacements");
    prim.morphTargets = static_cast<int>(targets);
    std::set<std::string> ignored;
    for (std::size_t t = 0; t < targets; ++t) {
      for (const auto& [attribute, accessor] : src.targets[t]) {
        std::vector<glm::vec3>* deltas = morphDeltas(prim, attribute);
        if (deltas == nullptr) {
          ignored.insert(attribute);
          continue;
        }
        const std::string where = name + " target " + str(t) + " " + attribute;
        auto values = readFloats(accessor, 3, count, where);
        if (!values) return values.error();
        if (deltas->empty()) deltas->assign(targets * count, glm::vec3(0.0f));
        const auto vectors = toVectors<glm::vec3>(*values);
        std::copy(vectors.begin(), vectors.end(), deltas->begin() + static_cast<std::ptrdiff_t>(t * count));
      }
    }
    if (!ignored.empty())
      warn(name + ": morph targets of " + joined(std::vector<std::string>(ignored.begin(), ignored.end())) +
           " are ignored (POSITION is morphed, and NORMAL and TANGENT where the primitive has them)");
    return Ok{};
  }

  // Where a target's displacements of `attribute` go, or nullptr when this engine
  // does not morph it (or the primitive lacks the attribute they would move).
  static std::vector<glm::vec3>* morphDeltas(PrimitiveData& prim, const std::string& attribute) {
    if (attribute == "POSITION") return &prim.morphPositions;
    if (attribute == "NORMAL" && !prim.normals.empty()) return &prim.morphNormals;
    if (attribute == "TANGENT" && !prim.tangents.empty()) return &prim.morphTangents;
    return nullptr;
  }

  Status readIndices(const tinygltf::Primitive& src, PrimitiveData& prim, const std::string& name) {
    if (src.indices < 0) return Ok{};
    auto values = readAccessor(gltf_, src.indices, file_ + ": " + name + " indices");
    if (!values) return values.error();
    if (values->components != 1) return error(name + " indices: must be SCALAR");
    prim.indices.resize(values->count);
    for (std::size_t i = 0; i < values->count; ++i) {
      double v = values->values[i];
      if (!(v >= 0.0) || v >= static_cast<double>(prim.positions.size()))
        return error(name + " indices: index " + str(i) + " = " + std::to_string(v) +
                     " is past the " + str(prim.positions.size()) + " vertices");
      prim.indices[i] = static_cast<std::uint32_t>(v);
    }
    return Ok{};
  }

  Status readSkinAttributes(const tinygltf::Primitive& src, PrimitiveData& prim, const std::string& name) {
    int sets = 0;
    for (int set = 0; set < 2; ++set) {
      std::string suffix = "_" + str(set);
      bool hasJoints = attribute(src, ("JOINTS" + suffix).c_str()) >= 0;
      bool hasWeights = attribute(src, ("WEIGHTS" + suffix).c_str()) >= 0;
      if (hasJoints != hasWeights) return error(name + ": JOINTS" + suffix + " and WEIGHTS" + suffix + " must come together");
      if (!hasJoints) break;
      sets = set + 1;
    }
    if (sets == 0) return Ok{};
    std::size_t count = prim.positions.size();
    prim.influences = sets * 4;
    std::size_t stride = static_cast<std::size_t>(prim.influences);
    prim.joints.assign(count * stride, 0);
    prim.weights.assign(count * stride, 0.0f);
    for (int set = 0; set < sets; ++set) {
      std::string jointsName = name + " JOINTS_" + str(set);
      auto joints = readAccessor(gltf_, attribute(src, ("JOINTS_" + str(set)).c_str()), file_ + ": " + jointsName);
      if (!joints) return joints.error();
      if (joints->components != 4 || joints->count != count)
        return error(jointsName + ": must be VEC4 with one element per vertex");
      auto weights = readFloats(attribute(src, ("WEIGHTS_" + str(set)).c_str()), 4, count, name + " WEIGHTS_" + str(set));
      if (!weights) return weights.error();
      for (std::size_t v = 0; v < count; ++v)
        for (std::size_t k = 0; k < 4; ++k) {
          double j = joints->values[v * 4 + k];
          if (!(j >= 0.0) || j > 65535.0) return error(jointsName + ": vertex " + str(v) + " has joint " + std::to_string(j));
          float w = (*weights)[v * 4 + k];
          if (w < 0.0f) return error(name + " WEIGHTS_" + str(set) + ": vertex " + str(v) + " has a negative weight");
          prim.joints[v * stride + static_cast<std::size_t>(set) * 4 + k] = static_cast<std::uint16_t>(j);
          prim.weights[v * stride + static_cast<std::size_t>(set) * 4 + k] = w;
        }
    }
    normaliseWeights(prim);
    return Ok{};
  }

  // Exporters often write weights that sum to 0.999 or 1.01; skinning assumes 1.
  // An all-zero vertex follows its first joint, as three.js does.
  static void normaliseWeights(PrimitiveData& prim) {
    std::size_t stride = static_cast<std::size_t>(prim.influences);
    for (std::size_t v = 0; v < prim.positions.size(); ++v) {
      float* w = &prim.weights[v * stride];
      float sum = 0.0f;
      for (std::size_t k = 0; k < stride; ++k) sum += w[k];
      if (sum > 0.0f) {
        for (std::size_t k = 0; k < stride; ++k) w[k] /= sum;
      } else {
        w[0] = 1.0f;
      }
    }
  }

  Status convertSkins() {
    for (std::size_t s = 0; s < gltf_.skins.size(); ++s) {
      const tinygltf::Skin& src = gltf_.skins[s];
      std::string name = "skin " + str(s);
      SkinData skin;
      skin.name = src.name;
      if (src.joints.empty()) return error(name + ": has no joints");
      for (std::size_t j = 0; j < src.joints.size(); ++j)
        if (!validIndex(src.joints[j], out_.nodes.size()))
          return error(name + ": joint " + str(j) + " has no node (node " + str(src.joints[j]) + ")");
      skin.joints = src.joints;
      skin.skeleton = validIndex(src.skeleton, out_.nodes.size()) ? src.skeleton : -1;
      skin.inverseBinds.assign(src.joints.size(), glm::mat4(1.0f));
      if (src.inverseBindMatrices >= 0) {
        auto m = readFloats(src.inverseBindMatrices, 16, 0, name + " inverseBindMatrices");
        if (!m) return m.error();
        if (m->size() / 16 < src.joints.size())
          return error(name + " inverseBindMatrices: " + str(m->size() / 16) + " matrices for " +
                       str(src.joints.size()) + " joints");
        for (std::size_t j = 0; j < src.joints.size(); ++j)
          for (int c = 0; c < 16; ++c) skin.inverseBinds[j][c / 4][c % 4] = (*m)[j * 16 + static_cast<std::size_t>(c)];
      }
      out_.skins.push_back(std::move(skin));
    }
    return Ok{};
  }

  // A vertex that names a joint past its skin's list would read outside the palette.
  Status checkSkinnedMeshes() {
    for (std::size_t n = 0; n < out_.nodes.size(); ++n) {
      const NodeData& node = out_.nodes[n];
      if (node.mesh < 0 || node.skin < 0) continue;
      std::size_t jointCount = out_.skins[static_cast<std::size_t>(node.skin)].joints.size();
      const MeshData& mesh = out_.meshes[static_cast<std::size_t>(node.mesh)];
      for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
        const PrimitiveData& prim = mesh.primitives[p];
        for (std::size_t i = 0; i < prim.joints.size(); ++i)
          if (prim.joints[i] >= jointCount && prim.weights[i] > 0.0f)
            return error("node " + str(n) + ": mesh " + str(node.mesh) + " primitive " + str(p) +
                         ": vertex " + str(i / static_cast<std::size_t>(prim.influences)) + " uses joint " +
                         str(static_cast<std::size_t>(prim.joints[i])) + " past skin " + str(node.skin) +
                         " of " + str(jointCount) + " joints");
      }
    }
    return Ok{};
  }

  Status convertAnimations() {
    for (std::size_t a = 0; a < gltf_.animations.size(); ++a) {
      AnimationData anim;
      anim.name = gltf_.animations[a].name;
      for (std::size_t c = 0; c < gltf_.animations[a].channels.size(); ++c) {
        if (Status s = convertChannel(gltf_.animations[a], c, anim, "animation " + str(a) + " channel " + str(c)); !s)
          return s;
      }
      out_.animations.push_back(std::move(anim));
    }
    return Ok{};
  }

  // Adds channel `c` to `anim` as a node or a morph weights channel (or skips it
  // with a warning when it has no target node).
  Status convertChannel(const tinygltf::Animation& src, std::size_t c, AnimationData& anim, const std::string& name) {
    const tinygltf::AnimationChannel& ch = src.channels[c];
    if (ch.target_node < 0) {
      warn(name + ": has no target node; ignored");
      return Ok{};
    }
    if (!validIndex(ch.target_node, out_.nodes.size()))
      return error(name + ": target node " + str(ch.target_node) + " does not exist");
    if (!validIndex(ch.sampler, src.samplers.size()))
      return error(name + ": sampler " + str(ch.sampler) + " does not exist");
    const tinygltf::AnimationSampler& sampler = src.samplers[static_cast<std::size_t>(ch.sampler)];
    const std::string samplerName = name + " sampler " + str(ch.sampler);
    if (ch.target_path == "weights") {
      MorphChannelData channel;
      if (Status s = convertMorphChannel(ch, sampler, channel, name, samplerName); !s) return s;
      anim.duration = std::max(anim.duration, channel.times.back());
      anim.morphChannels.push_back(std::move(channel));
      return Ok{};
    }
    ChannelData channel;
    channel.node = ch.target_node;
    if (ch.target_path == "translation") channel.path = AnimPath::Translation;
    else if (ch.target_path == "rotation") channel.path = AnimPath::Rotation;
    else if (ch.target_path == "scale") channel.path = AnimPath::Scale;
    else return error(name + ": unknown path \"" + ch.target_path + "\"");
    if (Status s = readKeys(sampler, samplerName, channel.interpolation, channel.times); !s) return s;
    if (Status s = readValues(sampler.output, channel, samplerName + " output"); !s) return s;
    anim.duration = std::max(anim.duration, channel.times.back());
    anim.channels.push_back(std::move(channel));
    return Ok{};
  }

  // A sampler's interpolation and key times, the same for node and weights channels.
  Status readKeys(const tinygltf::AnimationSampler& sampler, const std::string& name, Interpolation& interpolation,
                  std::vector<float>& times) {
    if (sampler.interpolation == "STEP") interpolation = Interpolation::Step;
    else if (sampler.interpolation == "CUBICSPLINE") interpolation = Interpolation::CubicSpline;
    else if (sampler.interpolation.empty() || sampler.interpolation == "LINEAR") interpolation = Interpolation::Linear;
    else return error(name + ": unknown interpolation \"" + sampler.interpolation + "\"");
    auto keys = readTimes(sampler.input, name + " input");
    if (!keys) return keys.error();
    times = std::move(keys).value();
    return Ok{};
  }

  // A `weights` channel drives every target of the node's mesh: the node must
  // have a mesh with targets, and the output holds one weight per target per key
  // (three blocks of them per key for CUBICSPLINE).
  Status convertMorphChannel(const tinygltf::AnimationChannel& ch, const tinygltf::AnimationSampler& sampler,
                             MorphChannelData& channel, const std::string& name, const std::string& samplerName) {
    const NodeData& node = out_.nodes[static_cast<std::size_t>(ch.target_node)];
    const int targets = node.mesh < 0 ? 0 : targetCount(out_.meshes[static_cast<std::size_t>(node.mesh)]);
    if (targets == 0)
      return error(name + ": animates the weights of node " + str(ch.target_node) +
                   (node.mesh < 0 ? ", which has no mesh" : ", whose mesh " + str(node.mesh) + " has no morph targets"));
    channel.node = ch.target_node;
    channel.targets = targets;
    if (Status s = readKeys(sampler, samplerName, channel.interpolation, channel.times); !s) return s;
    const std::size_t perKey = channel.interpolation == Interpolation::CubicSpline ? 3 : 1;
    const std::size_t expected = channel.times.size() * perKey * static_cast<std::size_t>(targets);
    auto values = readFloats(sampler.output, 1, 0, samplerName + " output");
    if (!values) return values.error();
    if (values->size() != expected)
      return error(samplerName + " output: " + str(values->size()) + " weights for " + str(channel.times.size()) +
                   " keys of " + str(targets) + " morph targets (" + str(expected) + " expected)");
    channel.values = std::move(values).value();
    return Ok{};
  }

  Result<std::vector<float>> readTimes(int accessor, const std::string& name) {
    auto times = readAccessor(gltf_, accessor, file_ + ": " + name);
    if (!times) return times.error();
    if (times->components != 1) return error(name + ": key times must be SCALAR");
    std::vector<float> out(times->count);
    for (std::size_t k = 0; k < times->count; ++k) {
      float t = static_cast<float>(times->values[k]);
      if (!std::isfinite(t)) return error(name + ": key " + str(k) + " time is NaN or infinite");
      if (t < 0.0f) return error(name + ": key " + str(k) + " time " + std::to_string(t) + " is negative");
      if (k > 0 && t < out[k - 1])
        return error(name + ": key " + str(k) + " time " + std::to_string(t) +
                     " is before the previous key (times must be sorted)");
      out[k] = t;
    }
    return out;
  }

  Status readValues(int accessor, ChannelData& channel, const std::string& name) {
    int components = channel.path == AnimPath::Rotation ? 4 : 3;
    std::size_t perKey = channel.interpolation == Interpolation::CubicSpline ? 3 : 1;
    auto values = readFloats(accessor, components, channel.times.size() * perKey, name);
    if (!values) return values.error();
    std::size_t count = values->size() / static_cast<std::size_t>(components);
    channel.values.resize(count, glm::vec4(0.0f));
    for (std::size_t i = 0; i < count; ++i)
      for (int c = 0; c < components; ++c)
        channel.values[i][c] = (*values)[i * static_cast<std::size_t>(components) + static_cast<std::size_t>(c)];
    return Ok{};
  }

  const tinygltf::Model& gltf_;
  ModelData& out_;
  std::string file_;
  int scene_ = -1;  // the scene asked for; -1 the file's default
};

}  // namespace

namespace {

Result<ModelData> convert(const std::vector<unsigned char>& bytes, const std::string& path,
                          const fs::path& folder, int scene = -1) {
  ModelData model;
  model.path = path;
  auto gltf = parseWithTinygltf(bytes, path, folder, model);
  if (!gltf) return gltf.error();
  Converter converter(*gltf, model, scene);
  if (Status s = converter.run(); !s) return s.error();
  for (const std::string& w : model.warnings) logWarning(w);
  return model;
}

}  // namespace

Result<ModelData> loadGltf(const std::string& path, int scene) {
  auto bytes = readFileBytes(path);
  if (!bytes) return bytes.error();
  std::error_code ec;
  fs::path folder = fs::weakly_canonical(fs::absolute(path).parent_path(), ec);
  if (ec || folder.empty()) return makeError(path + ": cannot resolve the model's folder");
  return convert(*bytes, path, folder, scene);
}

Result<ModelData> loadGltfFromMemory(std::span<const unsigned char> bytes, const std::string& name) {
  return convert(std::vector<unsigned char>(bytes.begin(), bytes.end()), name, fs::path());
}

}  // namespace engine
