#pragma once
// Buffers, vertex arrays, textures, renderbuffers and framebuffers.
#include <cstddef>
#include <span>
#include <string_view>

#include "core/result.h"
#include "gl/object.h"

namespace engine {
struct Image;
}

namespace engine::gl {

class Buffer : public Object<BufferDeleter> {
 public:
  Buffer() = default;
  // Immutable storage (glNamedBufferStorage) of `bytes` bytes, optionally filled.
  static Buffer create(std::size_t bytes, const void* data = nullptr,
                       GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
  template <typename T>
  static Buffer fromSpan(std::span<const T> items, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT) {
    return create(items.size_bytes(), items.data(), flags);
  }
  void upload(std::size_t offset, std::size_t bytes, const void* data) const;
  std::size_t size() const { return size_; }

 private:
  using Object::Object;
  std::size_t size_ = 0;
};

class VertexArray : public Object<VertexArrayDeleter> {
 public:
  VertexArray() = default;
  static VertexArray create();
  // Float attribute `location` read from `buffer` binding slot `binding`.
  void attribute(GLuint location, GLuint binding, GLint components, GLuint offset,
                 GLenum type = GL_FLOAT, bool normalized = false) const;
  // Integer attribute (joint indices).
  void integerAttribute(GLuint location, GLuint binding, GLint components, GLuint offset,
                        GLenum type) const;
  void vertexBuffer(GLuint binding, const Buffer& buffer, GLsizei stride, GLintptr offset = 0) const;
  void indexBuffer(const Buffer& buffer) const;
  void bind() const { glBindVertexArray(id()); }

 private:
  using Object::Object;
};

class Texture : public Object<TextureDeleter> {
 public:
  Texture() = default;
  // 2D texture with `levels` mip levels (0: full chain) of `format` (e.g. GL_SRGB8_ALPHA8).
  static Texture create2D(GLenum format, int width, int height, int levels = 1);
  static Texture create2DMultisample(GLenum format, int width, int height, int samples);
  // Takes ownership of a texture made elsewhere (e.g. a cube map).
  static Texture adopt(GLuint id, int width, int height) {
    Texture texture(id);
    texture.width_ = width;
    texture.height_ = height;
    return texture;
  }
  // An RGBA8 image (top row first) as a mipmapped, repeating, trilinear texture
  // whose uv (0,0) is the image's bottom-left; `srgb` for colour data.
  static Texture fromImage(const Image& image, bool srgb);
  // Uploads RGBA8 pixels, bottom row first (GL's order), into level 0.
  void uploadRgba8(const void* pixels) const;
  void generateMipmaps() const { glGenerateTextureMipmap(id()); }
  // Fills the mip chain from level 0 and samples it trilinearly, wrapping in s and t
  // as asked (GL_REPEAT, GL_CLAMP_TO_EDGE, ...).
  void mipmapTrilinear(GLint wrapS, GLint wrapT) const;
  // A square lookup table of `size` floats per texel (`format` GL_RED or GL_RGB,
  // stored as `internalFormat`), read linearly between texels and clamped at the
  // edges: the BRDF tables C++ computes and the shaders read.
  static Texture table(GLenum internalFormat, GLenum format, int size, const float* texels);
  // A buffer texture: `buffer`'s bytes as texels of `internalFormat` (GL_RGBA32F,
  // GL_RGB32F, GL_RGBA16UI...), which shaders read with texelFetch. llvmpipe
  // fetches a texel per lane in one load, where a storage buffer read at a
  // per-vertex index loops over the lanes once per component.
  static Texture ofBuffer(const Buffer& buffer, GLenum internalFormat);
  void parameter(GLenum name, GLint value) const { glTextureParameteri(id(), name, value); }
  void bind(GLuint unit) const { glBindTextureUnit(unit, id()); }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  using Object::Object;
  int width_ = 0;
  int height_ = 0;
};

// A sampler object: wrap modes and filters that override a texture's own on the
// unit it is bound to (glTF's samplers, which several textures may share and one
// image may be sampled through several of).
class Sampler : public Object<SamplerDeleter> {
 public:
  Sampler() = default;
  static Sampler create();
  void parameter(GLenum name, GLint value) const { glSamplerParameteri(id(), name, value); }
  void bind(GLuint unit) const { glBindSampler(unit, id()); }
  // Back to the texture's own parameters on `unit`.
  static void unbind(GLuint unit) { glBindSampler(unit, 0); }

 private:
  using Object::Object;
};

class Renderbuffer : public Object<RenderbufferDeleter> {
 public:
  Renderbuffer() = default;
  static Renderbuffer create(GLenum format, int width, int height, int samples = 0);

 private:
  using Object::Object;
};

class Framebuffer : public Object<FramebufferDeleter> {
 public:
  Framebuffer() = default;
  static Framebuffer create();
  void attach(GLenum attachment, const Texture& texture, int level = 0) const;
  void attach(GLenum attachment, const Renderbuffer& renderbuffer) const;
  // True when complete; otherwise fills `status` with the GL status code.
  bool complete(GLenum* status = nullptr) const;
  // Ok when complete; otherwise an error naming the framebuffer (`name`: what it is
  // for, "shadow-sun", "probe") and the GL status.
  Status check(std::string_view name) const;
  void bind() const { glBindFramebuffer(GL_FRAMEBUFFER, id()); }

 private:
  using Object::Object;
};

// What a framebuffer object someone else made holds: enough to tell whether a
// renderer may draw into it as it is. Zero sizes where an attachment is missing;
// the default framebuffer (0) reads as all zeros.
struct FramebufferLayout {
  int width = 0, height = 0;  // of colour attachment 0
  int samples = 0;
  int colorBits[4] = {0, 0, 0, 0};
  GLenum colorType = GL_NONE;  // GL_UNSIGNED_NORMALIZED, GL_FLOAT...
  int depthBits = 0;
  GLenum depthType = GL_NONE;
  // Colour attachment 0's image, where another framebuffer can attach it too: a
  // renderbuffer, or level `colorLevel` of a 2D texture (GL_NONE otherwise).
  GLenum colorObjectType = GL_NONE;
  GLuint colorObject = 0;
  int colorLevel = 0;
};
FramebufferLayout framebufferLayout(GLuint framebuffer);

// A query object (primitives generated, time elapsed...) of one target.
class Query : public Object<QueryDeleter> {
 public:
  Query() = default;
  static Query create(GLenum target);
  void begin() const { glBeginQuery(target_, id()); }
  void end() const { glEndQuery(target_); }
  // Waits for the result: for benchmarks and tools, not inside a frame.
  GLuint64 result() const;
  // Whether result() would return without waiting.
  bool available() const;

 private:
  Query(GLuint id, GLenum target) : Object(id), target_(target) {}
  GLenum target_ = 0;
};

}  // namespace engine::gl
