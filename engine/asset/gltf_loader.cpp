// Parsing (tinygltf, after the guard's checks) and the loader's public face; the
// other concerns are in gltf_loader_*.cpp, which share gltf_loader_impl.h.
#include "asset/gltf_loader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "asset/gltf_compression.h"
#include "asset/gltf_loader_impl.h"
#include "core/log.h"

namespace engine {
namespace {

namespace fs = std::filesystem;

}  // namespace

namespace gltf_loader {
namespace {

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

Status Converter::run() {
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

}  // namespace gltf_loader

Result<ModelData> loadGltf(const std::string& path, int scene) {
  auto bytes = gltf_loader::readFileBytes(path);
  if (!bytes) return bytes.error();
  std::error_code ec;
  fs::path folder = fs::weakly_canonical(fs::absolute(path).parent_path(), ec);
  if (ec || folder.empty()) return makeError(path + ": cannot resolve the model's folder");
  return gltf_loader::convert(*bytes, path, folder, scene);
}

Result<ModelData> loadGltfFromMemory(std::span<const unsigned char> bytes, const std::string& name) {
  return gltf_loader::convert(std::vector<unsigned char>(bytes.begin(), bytes.end()), name, fs::path());
}

}  // namespace engine
