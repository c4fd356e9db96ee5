#pragma once
// RAII, move-only owners of GL object names (Magnum's habit): a Buffer deletes its
// name when it goes out of scope, cannot be copied, and a moved-from one owns
// nothing. Every object is created with the 4.5 DSA entry points (glCreate*), so it
// is complete without being bound.
#include <glad/gl.h>

#include <cstdio>
#include <utility>

namespace engine::gl {

// Bookkeeping of every owner, for the soak test and for a bug that would otherwise
// pass unseen: a name deleted once its context is gone (GL then has no current
// context to delete it in). Each GlContext counts itself in contextsAlive.
namespace detail {
inline int contextsAlive = 0;
inline long long objectsAlive = 0;
inline long long objectsOrphaned = 0;

inline void orphaned(GLuint id) {
  if (objectsOrphaned++ == 0) {
    std::fprintf(stderr, "gl: GL object %u outlived its context (a bug: it is left undeleted)\n", id);
  }
}
}  // namespace detail

// GL objects owned now, and those whose owner died after every context had gone.
inline long long liveObjects() { return detail::objectsAlive; }
inline long long orphanedObjects() { return detail::objectsOrphaned; }

// Deleter is a function object taking the name to delete.
template <typename Deleter>
class Object {
 public:
  Object() = default;
  explicit Object(GLuint id) : id_(id) {
    if (id_) ++detail::objectsAlive;
  }
  ~Object() { reset(); }
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;
  Object(Object&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  Object& operator=(Object&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }

  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (!id_) return;
    --detail::objectsAlive;
    if (detail::contextsAlive > 0) {
      Deleter{}(id_);
    } else {
      detail::orphaned(id_);
    }
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

struct BufferDeleter { void operator()(GLuint id) const { glDeleteBuffers(1, &id); } };
struct VertexArrayDeleter { void operator()(GLuint id) const { glDeleteVertexArrays(1, &id); } };
struct TextureDeleter { void operator()(GLuint id) const { glDeleteTextures(1, &id); } };
struct FramebufferDeleter { void operator()(GLuint id) const { glDeleteFramebuffers(1, &id); } };
struct RenderbufferDeleter { void operator()(GLuint id) const { glDeleteRenderbuffers(1, &id); } };
struct ProgramDeleter { void operator()(GLuint id) const { glDeleteProgram(id); } };
struct ShaderDeleter { void operator()(GLuint id) const { glDeleteShader(id); } };
struct SamplerDeleter { void operator()(GLuint id) const { glDeleteSamplers(1, &id); } };
struct QueryDeleter { void operator()(GLuint id) const { glDeleteQueries(1, &id); } };

}  // namespace engine::gl
