#pragma once
// Shader programs built from GLSL files under a shader folder (shaders/), with
// `#include "file.glsl"` and per-variant `#define`s. Compile and link errors name
// the file and line the driver complained about, not the line of the flattened
// source.
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/result.h"
#include "gl/object.h"

namespace engine::gl {

// The flattened source of one stage and the files its `#line` numbers refer to.
struct PreprocessedSource {
  std::string text;
  std::vector<std::string> files;  // index = GLSL source-string number
};

// Resolves includes (relative to the shader folder), each file once, rejecting
// cycles and paths that leave the folder; `defines` go right after `#version`.
Result<PreprocessedSource> preprocessShader(const std::string& shaderDir, const std::string& file,
                                            const std::vector<std::string>& defines = {});

// The names of the uniforms `source` declares (`uniform float a, b[4];` gives a and b;
// uniform blocks are skipped): every branch of its #ifdefs, so a name a variant's
// compiler optimised away is still declared. Sorted, each name once.
std::vector<std::string> declaredUniforms(const std::string& source);

// Every (program, name) a Program was asked to set that none of its stages' sources
// declares: a misspelt or stale name, which GL would ignore silently. Each is also
// written to stderr once. Tests check it stays empty over the scenes they draw.
std::vector<std::string> undeclaredUniformsSet();
void forgetUndeclaredUniforms();  // for a test that provokes one

// Rewrites a driver log ("0:12(5): error: ...") with file names ("scene.frag:12(5): ...").
std::string translateShaderLog(const std::string& log, const std::vector<std::string>& files);

struct ShaderStage {
  GLenum type;       // GL_VERTEX_SHADER, ...
  std::string file;  // relative to the shader folder
};

class Program : public Object<ProgramDeleter> {
 public:
  Program() = default;
  // `feedbackVaryings`: outputs captured by transform feedback (interleaved).
  static Result<Program> build(const std::string& shaderDir, const std::vector<ShaderStage>& stages,
                               const std::vector<std::string>& defines = {},
                               const std::vector<std::string>& feedbackVaryings = {});

  void use() const { glUseProgram(id()); }
  // -1 for a name the linked program does not use (GL ignores a set of -1); a name
  // no stage declares is also reported (undeclaredUniformsSet).
  GLint location(const char* name) const;
  void set(const char* name, int value) const { glProgramUniform1i(id(), location(name), value); }
  void set(const char* name, float value) const { glProgramUniform1f(id(), location(name), value); }
  void set(const char* name, const glm::vec2& v) const;
  void set(const char* name, const glm::vec3& v) const;
  void set(const char* name, const glm::vec4& v) const;
  void set(const char* name, const glm::mat4& m) const;
  void set(const char* name, const glm::mat3& m) const;

 private:
  using Object::Object;
  // Uniform locations by name; filled lazily, so a program's map stays small.
  mutable std::map<std::string, GLint, std::less<>> locations_;
  // What the stages' sources declare (declaredUniforms) and their files, for the report.
  std::shared_ptr<const std::vector<std::string>> declared_;
  std::string files_;
};

}  // namespace engine::gl
