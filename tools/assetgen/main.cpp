// assetgen: writes the project's own animated character (assets/models/character.*)
// and the material test model (assets/models/materials.*) as glTF 2.0.
// Usage: assetgen [--out DIR]. Exit codes: 0 written, 2 bad options or an output
// folder that cannot be written.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <string>

#include "assetgen.h"

namespace {

constexpr int kExitBadInput = 2;
constexpr const char* kBaseName = "character";
constexpr const char* kMaterialsBaseName = "materials";

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Writes the project's skinned, animated robot and its material test model as glTF 2.0 (.gltf, .bin, .png)."};
  std::string out = "assets/models";
  app.add_option("--out", out, "output folder (created when missing)")->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "assetgen: %s\n", e.what());
    return kExitBadInput;
  }
  const assetgen::Character robot = assetgen::buildRobot();
  if (auto written = assetgen::writeCharacter(robot, out, kBaseName); !written) {
    std::fprintf(stderr, "assetgen: %s\n", written.error().message.c_str());
    return kExitBadInput;
  }
  const assetgen::OutputNames names = assetgen::outputNames(kBaseName);
  std::printf("wrote %s/%s (%zu joints, %zu vertices, %zu triangles, %zu clips), %s, %s\n",
              out.c_str(), names.gltf.c_str(), robot.joints.size(), robot.vertices.size(),
              robot.indices.size() / 3, robot.clips.size(), names.bin.c_str(), names.image.c_str());
  if (auto written = assetgen::writeMaterialsModel(out, kMaterialsBaseName); !written) {
    std::fprintf(stderr, "assetgen: %s\n", written.error().message.c_str());
    return kExitBadInput;
  }
  std::printf("wrote %s/%s.gltf (the material test model), %s.bin, %s_*.png\n", out.c_str(), kMaterialsBaseName,
              kMaterialsBaseName, kMaterialsBaseName);
  return 0;
}
