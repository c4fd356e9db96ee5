#include "assetgen.h"

#include <filesystem>
#include <fstream>
#include <system_error>

#include "gltf_writer.h"
#include "materials_model.h"
#include "robot_clips.h"
#include "robot_mesh.h"
#include "robot_rig.h"
#include "robot_texture.h"

namespace assetgen {

namespace fs = std::filesystem;

namespace {

engine::Status writeBytes(const fs::path& path, const void* data, size_t size) {
  const fs::path tmp = fs::path(path).concat(".tmp");
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (out) out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) {
      std::error_code ignored;
      fs::remove(tmp, ignored);
      return engine::makeError(path.string() + ": cannot write file");
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    return engine::makeError(path.string() + ": cannot write file: " + ec.message());
  }
  return engine::Ok{};
}

engine::Status prepareFolder(const fs::path& folder) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec || !fs::is_directory(folder)) {
    return engine::makeError(folder.string() + ": cannot create output folder" +
                             (ec ? ": " + ec.message() : ""));
  }
  return engine::Ok{};
}

}  // namespace

OutputNames outputNames(const std::string& baseName) {
  return {baseName + ".gltf", baseName + ".bin", baseName + "_albedo.png"};
}

Character buildRobot() {
  Character robot;
  robot.name = "Robot";
  robot.joints = robotSkeleton();
  const std::vector<BodyPart> parts = robotBodyParts();
  for (const BodyPart& part : parts) appendBodyPart(part, robot.vertices, robot.indices);
  robot.albedo = paintRobotAlbedo(parts);
  robot.clips = robotClips(robot.joints);
  return robot;
}

engine::Status writeCharacter(const Character& character, const std::string& folder,
                              const std::string& baseName) {
  if (auto ready = prepareFolder(folder); !ready) return ready;
  const OutputNames names = outputNames(baseName);
  const fs::path dir(folder);
  const GltfFiles files = toGltf(character, names.bin, names.image);
  if (auto bin = writeBytes(dir / names.bin, files.bin.data(), files.bin.size()); !bin) return bin;
  if (auto png = engine::writePng((dir / names.image).string(), character.albedo); !png) return png;
  return writeBytes(dir / names.gltf, files.json.data(), files.json.size());
}

engine::Status writeMaterialsModel(const std::string& folder, const std::string& baseName) {
  if (auto ready = prepareFolder(folder); !ready) return ready;
  const fs::path dir(folder);
  const MaterialsModel model = buildMaterialsModel(baseName);
  if (auto bin = writeBytes(dir / (baseName + ".bin"), model.bin.data(), model.bin.size()); !bin) return bin;
  for (const auto& [name, image] : model.images) {
    if (auto png = engine::writePng((dir / name).string(), image); !png) return png;
  }
  return writeBytes(dir / (baseName + ".gltf"), model.json.data(), model.json.size());
}

}  // namespace assetgen
