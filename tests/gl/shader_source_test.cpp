// The shader preprocessor needs no GL: includes, defines, #line bookkeeping and the
// translation of driver logs back to file names.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "asset/model_data.h"
#include "gl/shader.h"

using namespace engine;
namespace fs = std::filesystem;

class ShaderSource : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("engine_shaders_" + std::to_string(::getpid()));
    fs::create_directories(dir_ / "inc");
  }
  void TearDown() override { fs::remove_all(dir_); }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
  }
  fs::path dir_;
};

TEST_F(ShaderSource, IncludesOnceWithLineDirectives) {
  write("inc/a.glsl", "float a() { return 1.0; }\n");
  write("main.frag", "#version 450 core\n#include \"inc/a.glsl\"\n#include \"inc/a.glsl\"\nvoid main() {}\n");
  auto src = gl::preprocessShader(dir_.string(), "main.frag", {"SKINNED 1"});
  ASSERT_TRUE(src.ok()) << src.error().message;
  EXPECT_EQ(src->text.rfind("#version 450 core\n#define SKINNED 1\n", 0), 0u);
  EXPECT_EQ(src->files, (std::vector<std::string>{"main.frag", "inc/a.glsl"}));
  // a.glsl's body appears once, and main.frag resumes at its line 4 afterwards.
  const auto first = src->text.find("float a()");
  ASSERT_NE(first, std::string::npos);
  EXPECT_EQ(src->text.find("float a()", first + 1), std::string::npos);
  EXPECT_NE(src->text.find("#line 1 1\nfloat a()"), std::string::npos);
  EXPECT_NE(src->text.find("#line 4 0\nvoid main()"), std::string::npos);
}

TEST_F(ShaderSource, CycleIsAnError) {
  write("x.glsl", "#include \"y.glsl\"\n");
  write("y.glsl", "#include \"x.glsl\"\n");
  write("main.vert", "#version 450 core\n#include \"x.glsl\"\n");
  auto src = gl::preprocessShader(dir_.string(), "main.vert");
  ASSERT_FALSE(src.ok());
  EXPECT_NE(src.error().message.find("y.glsl:1: include cycle"), std::string::npos) << src.error().message;
}

TEST_F(ShaderSource, MissingIncludeNamesFileAndLine) {
  write("main.vert", "#version 450 core\n\n#include \"nowhere.glsl\"\n");
  auto src = gl::preprocessShader(dir_.string(), "main.vert");
  ASSERT_FALSE(src.ok());
  EXPECT_NE(src.error().message.find("main.vert:3: cannot include \"nowhere.glsl\""), std::string::npos)
      << src.error().message;
}

TEST_F(ShaderSource, IncludeMayNotLeaveTheFolder) {
  write("main.vert", "#version 450 core\n#include \"../secret.glsl\"\n");
  auto src = gl::preprocessShader(dir_.string(), "main.vert");
  ASSERT_FALSE(src.ok());
  EXPECT_NE(src.error().message.find("leaves the shader folder"), std::string::npos);
}

TEST_F(ShaderSource, VersionMustComeFirst) {
  write("main.vert", "void main() {}\n");
  auto src = gl::preprocessShader(dir_.string(), "main.vert");
  ASSERT_FALSE(src.ok());
  EXPECT_NE(src.error().message.find("main.vert:1"), std::string::npos);
}

TEST(ShaderLog, MesaAndNvidiaFormatsGetFileNames) {
  const std::vector<std::string> files = {"scene.frag", "common/shading.glsl"};
  EXPECT_EQ(gl::translateShaderLog("0:12(5): error: bad\n1:3(1): error: worse\n", files),
            "scene.frag:12(5): error: bad\ncommon/shading.glsl:3(1): error: worse");
  EXPECT_EQ(gl::translateShaderLog("1(7) : error C0000: syntax error", files),
            "common/shading.glsl:7 : error C0000: syntax error");
}

// Every binding in the shipped shaders names engine/gl/bindings.h's define, never a
// number that C++ could bind differently (the test shaders are exempt: they are
// driven by their own tests). The defines reach every program.
TEST(ShaderBindings, ShippedShadersNameTheirBindings) {
  const std::regex numbered(R"(binding\s*=\s*[0-9])");
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(std::string(ENGINE_SOURCE_DIR) + "/shaders")) {
    if (!entry.is_regular_file() || entry.path().parent_path().filename() == "test") continue;
    ++files;
    std::ifstream in(entry.path());
    std::string line;
    for (int n = 1; std::getline(in, line); ++n)
      EXPECT_FALSE(std::regex_search(line, numbered)) << entry.path().string() << ":" << n << ": " << line;
  }
  EXPECT_GT(files, 20);
  auto src = gl::preprocessShader(std::string(ENGINE_SOURCE_DIR) + "/shaders", "scene.frag");
  ASSERT_TRUE(src.ok()) << src.error().message;
  EXPECT_NE(src->text.find("#define UNIT_BASE_COLOR 0\n"), std::string::npos);
  EXPECT_NE(src->text.find("#define BUFFER_MORPH_WEIGHTS 2\n"), std::string::npos);
}

// material.glsl's slot numbers index the per-slot uv transforms that C++ uploads
// in engine::TextureSlot order: each must be that enum's value.
TEST(ShaderBindings, MaterialSlotsAreTextureSlotNumbers) {
  std::ifstream in(std::string(ENGINE_SOURCE_DIR) + "/shaders/common/material.glsl");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::pair<const char*, TextureSlot> slots[] = {{"SLOT_BASE_COLOR", TextureSlot::BaseColor},
                                                       {"SLOT_NORMAL", TextureSlot::Normal},
                                                       {"SLOT_METALLIC_ROUGHNESS", TextureSlot::MetallicRoughness},
                                                       {"SLOT_EMISSIVE", TextureSlot::Emissive},
                                                       {"SLOT_OCCLUSION", TextureSlot::Occlusion},
                                                       {"SLOT_SPECULAR", TextureSlot::Specular},
                                                       {"SLOT_SPECULAR_COLOR", TextureSlot::SpecularColor},
                                                       {"SLOT_CLEARCOAT", TextureSlot::Clearcoat},
                                                       {"SLOT_CLEARCOAT_ROUGHNESS", TextureSlot::ClearcoatRoughness},
                                                       {"SLOT_TRANSMISSION", TextureSlot::Transmission},
                                                       {"SLOT_THICKNESS", TextureSlot::Thickness},
                                                       {"SLOT_CLEARCOAT_NORMAL", TextureSlot::ClearcoatNormal},
                                                       {"SLOT_SHEEN_COLOR", TextureSlot::SheenColor},
                                                       {"SLOT_SHEEN_ROUGHNESS", TextureSlot::SheenRoughness},
                                                       {"SLOT_ANISOTROPY", TextureSlot::Anisotropy},
                                                       {"SLOT_IRIDESCENCE", TextureSlot::Iridescence},
                                                       {"SLOT_IRIDESCENCE_THICKNESS", TextureSlot::IridescenceThickness}};
  for (const auto& [name, slot] : slots) {
    const std::regex declared("const int " + std::string(name) + " = ([0-9]+);");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(text, m, declared)) << name;
    EXPECT_EQ(std::stoi(m[1]), static_cast<int>(slot)) << name;
  }
  EXPECT_EQ(kTextureSlots, 17);
  // The per-slot arrays are sized for every slot.
  EXPECT_NE(text.find("uniform mat3 u_uvTransform[" + std::to_string(kTextureSlots) + "];"), std::string::npos);
  EXPECT_NE(text.find("uniform int u_texCoord[" + std::to_string(kTextureSlots) + "];"), std::string::npos);
}

// What Program::location checks a missing name against: every declarator of every
// plain uniform, whatever #ifdef it sits under; not a block's members.
TEST(DeclaredUniforms, EveryDeclaratorOfEveryPlainUniform) {
  const std::string source = R"(#version 450
layout(binding = 0) uniform sampler2D u_tex;
uniform highp float u_a, u_b[4], u_c = 1.0;
#ifdef NEVER
uniform vec3 u_hidden;
#endif
uniform Light u_lights[2];
layout(std140, binding = 1) uniform Frame { mat4 u_inBlock; } frame;
float uniformity;  // not a declaration
void main() {}
)";
  EXPECT_EQ(gl::declaredUniforms(source),
            (std::vector<std::string>{"u_a", "u_b", "u_c", "u_hidden", "u_lights", "u_tex"}));
  EXPECT_TRUE(gl::declaredUniforms("void main() {}").empty());
  EXPECT_TRUE(gl::declaredUniforms("uniform").empty());  // cut off: no crash, nothing
}
