#include "gl/shader.h"

#include "gl/bindings.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <regex>
#include <set>
#include <sstream>
#include <string_view>

namespace engine::gl {
namespace fs = std::filesystem;
namespace {

Result<std::string> readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return makeError(path.string() + ": cannot open shader file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Parses `#include "name"`; returns the name, or empty when the line is not one.
std::string includeTarget(const std::string& line) {
  static const std::regex re(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
  std::smatch m;
  return std::regex_match(line, m, re) ? m[1].str() : std::string();
}

bool isVersionLine(const std::string& line) {
  return line.find("#version") != std::string::npos;
}

struct Preprocessor {
  fs::path root;
  PreprocessedSource out;
  std::set<std::string> done;       // files already included (each file once)
  std::vector<std::string> stack;   // files being included (cycle detection)

  Status include(const std::string& name, const std::string& from, int fromLine,
                 const std::vector<std::string>* defines) {
    const fs::path rel = fs::path(name).lexically_normal();
    if (rel.is_absolute() || rel.empty() || *rel.begin() == "..") {
      return makeError(from + ":" + std::to_string(fromLine) + ": include \"" + name +
                       "\" leaves the shader folder");
    }
    const std::string key = rel.generic_string();
    for (const auto& open : stack) {
      if (open == key) {
        return makeError(from + ":" + std::to_string(fromLine) + ": include cycle through \"" +
                         key + "\"");
      }
    }
    if (done.count(key)) return Ok{};
    done.insert(key);
    auto text = readText(root / rel);
    if (!text) {
      if (from.empty()) return text.error();
      return makeError(from + ":" + std::to_string(fromLine) + ": cannot include \"" + key + "\"");
    }
    stack.push_back(key);
    const int fileIndex = static_cast<int>(out.files.size());
    out.files.push_back(key);

    std::istringstream lines(*text);
    std::string line;
    int lineNo = 0;
    if (defines) {
      // The top file: #version must stay the very first line, defines follow it.
      std::getline(lines, line);
      lineNo = 1;
      if (!isVersionLine(line)) {
        return makeError(key + ":1: the first line must be a #version directive");
      }
      out.text += line + "\n";
      for (const auto& d : *defines) out.text += "#define " + d + "\n";
      for (const auto& b : binding::kDefines) out.text += "#define " + std::string(b.name) + " " + std::to_string(b.value) + "\n";
    }
    out.text += "#line " + std::to_string(lineNo + 1) + " " + std::to_string(fileIndex) + "\n";
    while (std::getline(lines, line)) {
      ++lineNo;
      const std::string target = includeTarget(line);
      if (target.empty()) {
        out.text += line + "\n";
        continue;
      }
      if (auto s = include(target, key, lineNo, nullptr); !s) return s;
      out.text += "#line " + std::to_string(lineNo + 1) + " " + std::to_string(fileIndex) + "\n";
    }
    stack.pop_back();
    return Ok{};
  }
};

Result<GLuint> compileStage(GLenum type, const PreprocessedSource& source) {
  const GLuint shader = glCreateShader(type);
  const char* text = source.text.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok) return shader;
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<size_t>(length > 0 ? length : 1), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  glDeleteShader(shader);
  return makeError(translateShaderLog(log.c_str(), source.files));
}

bool isIdentifierChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// The identifier at `at` (after blanks), and the position after it.
std::string_view identifierAt(std::string_view text, size_t& at) {
  while (at < text.size() && std::isspace(static_cast<unsigned char>(text[at]))) ++at;
  const size_t start = at;
  while (at < text.size() && isIdentifierChar(text[at])) ++at;
  return text.substr(start, at - start);
}

bool isQualifier(std::string_view word) {
  return word == "highp" || word == "mediump" || word == "lowp" || word == "restrict" || word == "readonly" ||
         word == "writeonly" || word == "coherent" || word == "volatile" || word == "flat";
}

std::mutex& undeclaredMutex() {
  static std::mutex m;
  return m;
}
std::vector<std::string>& undeclaredList() {
  static std::vector<std::string> list;
  return list;
}

}  // namespace

std::vector<std::string> declaredUniforms(const std::string& source) {
  std::vector<std::string> names;
  const std::string_view text(source);
  for (size_t at = text.find("uniform"); at != std::string_view::npos; at = text.find("uniform", at)) {
    const bool word = (at == 0 || !isIdentifierChar(text[at - 1])) &&
                      (at + 7 >= text.size() || !isIdentifierChar(text[at + 7]));
    at += 7;
    if (!word) continue;
    std::string_view type = identifierAt(text, at);
    while (isQualifier(type)) type = identifierAt(text, at);
    const size_t end = text.find(';', at);
    if (type.empty() || end == std::string_view::npos) continue;
    const size_t brace = text.find('{', at);
    if (brace < end) continue;  // a uniform block: its members are not set by name
    // Declarators up to the ';': "a", "b[4]", "c = 1.0".
    while (at < end) {
      const std::string_view name = identifierAt(text, at);
      if (!name.empty()) names.emplace_back(name);
      const size_t comma = text.find(',', at);
      at = comma < end ? comma + 1 : end;
    }
  }
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  return names;
}

std::vector<std::string> undeclaredUniformsSet() {
  std::lock_guard lock(undeclaredMutex());
  return undeclaredList();
}

void forgetUndeclaredUniforms() {
  std::lock_guard lock(undeclaredMutex());
  undeclaredList().clear();
}

Result<PreprocessedSource> preprocessShader(const std::string& shaderDir, const std::string& file,
                                            const std::vector<std::string>& defines) {
  Preprocessor p{fs::path(shaderDir), {}, {}, {}};
  if (auto s = p.include(file, "", 0, &defines); !s) return s.error();
  return std::move(p.out);
}

std::string translateShaderLog(const std::string& log, const std::vector<std::string>& files) {
  // Mesa and NVIDIA both start a message with "<string>:<line>" or "<string>(<line>)".
  static const std::regex re(R"((^|\n)\s*(\d+)([:(])(\d+))");
  std::string out;
  auto begin = log.cbegin();
  std::smatch m;
  while (std::regex_search(begin, log.cend(), m, re)) {
    out.append(begin, m[0].first);
    const size_t index = std::stoul(m[2].str());
    const std::string name = index < files.size() ? files[index] : m[2].str();
    out += m[1].str() + name + ":" + m[4].str();
    begin = m[0].second;
    if (m[3].str() == "(" && begin != log.cend() && *begin == ')') ++begin;
  }
  out.append(begin, log.cend());
  while (!out.empty() && (out.back() == '\n' || out.back() == '\0')) out.pop_back();
  return out;
}

Result<Program> Program::build(const std::string& shaderDir, const std::vector<ShaderStage>& stages,
                               const std::vector<std::string>& defines,
                               const std::vector<std::string>& feedbackVaryings) {
  std::vector<GLuint> shaders;
  auto cleanup = [&] {
    for (GLuint s : shaders) glDeleteShader(s);
  };
  std::string names;
  std::vector<std::string> declared;
  for (const auto& stage : stages) {
    auto source = preprocessShader(shaderDir, stage.file, defines);
    if (!source) {
      cleanup();
      return source.error();
    }
    auto shader = compileStage(stage.type, *source);
    if (!shader) {
      cleanup();
      return shader.error();
    }
    shaders.push_back(*shader);
    names += (names.empty() ? "" : " + ") + stage.file;
    const auto stageNames = declaredUniforms(source->text);
    declared.insert(declared.end(), stageNames.begin(), stageNames.end());
  }
  Program program(glCreateProgram());
  for (GLuint s : shaders) glAttachShader(program.id(), s);
  if (!feedbackVaryings.empty()) {
    std::vector<const char*> varyings;
    for (const auto& v : feedbackVaryings) varyings.push_back(v.c_str());
    glTransformFeedbackVaryings(program.id(), GLsizei(varyings.size()), varyings.data(),
                                GL_INTERLEAVED_ATTRIBS);
  }
  glLinkProgram(program.id());
  cleanup();
  GLint ok = GL_FALSE;
  glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(program.id(), GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<size_t>(length > 0 ? length : 1), '\0');
    glGetProgramInfoLog(program.id(), length, nullptr, log.data());
    return makeError(names + ": link failed: " + std::string(log.c_str()));
  }
  std::sort(declared.begin(), declared.end());
  declared.erase(std::unique(declared.begin(), declared.end()), declared.end());
  program.declared_ = std::make_shared<const std::vector<std::string>>(std::move(declared));
  program.files_ = std::move(names);
  return program;
}

GLint Program::location(const char* name) const {
  auto it = locations_.find(std::string_view(name));
  if (it != locations_.end()) return it->second;
  const GLint loc = glGetUniformLocation(id(), name);
  locations_.emplace(name, loc);
  if (loc < 0 && declared_) {
    // "lights[2].color" is declared as "lights".
    const std::string_view full(name);
    const std::string base(full.substr(0, full.find_first_of("[.")));
    if (!std::binary_search(declared_->begin(), declared_->end(), base)) {
      const std::string entry = files_ + ": " + std::string(full);
      std::lock_guard lock(undeclaredMutex());
      auto& list = undeclaredList();
      if (std::find(list.begin(), list.end(), entry) == list.end()) {
        list.push_back(entry);
        std::fprintf(stderr, "warning: %s is set but no stage declares it\n", entry.c_str());
      }
    }
  }
  return loc;
}

void Program::set(const char* name, const glm::vec2& v) const {
  glProgramUniform2fv(id(), location(name), 1, glm::value_ptr(v));
}
void Program::set(const char* name, const glm::vec3& v) const {
  glProgramUniform3fv(id(), location(name), 1, glm::value_ptr(v));
}
void Program::set(const char* name, const glm::vec4& v) const {
  glProgramUniform4fv(id(), location(name), 1, glm::value_ptr(v));
}
void Program::set(const char* name, const glm::mat4& m) const {
  glProgramUniformMatrix4fv(id(), location(name), 1, GL_FALSE, glm::value_ptr(m));
}
void Program::set(const char* name, const glm::mat3& m) const {
  glProgramUniformMatrix3fv(id(), location(name), 1, GL_FALSE, glm::value_ptr(m));
}

}  // namespace engine::gl
