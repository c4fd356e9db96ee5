#include "gl/resources.h"

#include <cstdio>
#include <string>

#include <glm/glm.hpp>

#include "core/image.h"

namespace engine::gl {

Buffer Buffer::create(std::size_t bytes, const void* data, GLbitfield flags) {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  glNamedBufferStorage(id, static_cast<GLsizeiptr>(bytes), data, flags);
  Buffer buffer(id);
  buffer.size_ = bytes;
  return buffer;
}

void Buffer::upload(std::size_t offset, std::size_t bytes, const void* data) const {
  glNamedBufferSubData(id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
}

VertexArray VertexArray::create() {
  GLuint id = 0;
  glCreateVertexArrays(1, &id);
  return VertexArray(id);
}

void VertexArray::attribute(GLuint location, GLuint binding, GLint components, GLuint offset,
                            GLenum type, bool normalized) const {
  glEnableVertexArrayAttrib(id(), location);
  glVertexArrayAttribFormat(id(), location, components, type, normalized ? GL_TRUE : GL_FALSE, offset);
  glVertexArrayAttribBinding(id(), location, binding);
}

void VertexArray::integerAttribute(GLuint location, GLuint binding, GLint components,
                                   GLuint offset, GLenum type) const {
  glEnableVertexArrayAttrib(id(), location);
  glVertexArrayAttribIFormat(id(), location, components, type, offset);
  glVertexArrayAttribBinding(id(), location, binding);
}

void VertexArray::vertexBuffer(GLuint binding, const Buffer& buffer, GLsizei stride,
                               GLintptr offset) const {
  glVertexArrayVertexBuffer(id(), binding, buffer.id(), offset, stride);
}

void VertexArray::indexBuffer(const Buffer& buffer) const {
  glVertexArrayElementBuffer(id(), buffer.id());
}

Texture Texture::create2D(GLenum format, int width, int height, int levels) {
  if (levels <= 0) {
    levels = 1;
    for (int size = width > height ? width : height; size > 1; size /= 2) ++levels;
  }
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &id);
  glTextureStorage2D(id, levels, format, width, height);
  Texture texture(id);
  texture.width_ = width;
  texture.height_ = height;
  return texture;
}

Sampler Sampler::create() {
  GLuint id = 0;
  glCreateSamplers(1, &id);
  return Sampler(id);
}

Texture Texture::create2DMultisample(GLenum format, int width, int height, int samples) {
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &id);
  // Fixed sample locations keep resolves identical between runs and backends.
  glTextureStorage2DMultisample(id, samples, format, width, height, GL_TRUE);
  Texture texture(id);
  texture.width_ = width;
  texture.height_ = height;
  return texture;
}

Texture Texture::fromImage(const Image& image, bool srgb) {
  Texture texture = create2D(srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, image.width, image.height, 0);
  // GL's first row is the bottom one; uv (0,0) then samples the image's bottom-left.
  Image flipped = image;
  flipVertically(flipped);
  texture.uploadRgba8(flipped.pixels.data());
  texture.mipmapTrilinear(GL_REPEAT, GL_REPEAT);
  return texture;
}

void Texture::mipmapTrilinear(GLint wrapS, GLint wrapT) const {
  generateMipmaps();
  parameter(GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  parameter(GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  parameter(GL_TEXTURE_WRAP_S, wrapS);
  parameter(GL_TEXTURE_WRAP_T, wrapT);
}

Texture Texture::table(GLenum internalFormat, GLenum format, int size, const float* texels) {
  Texture texture = create2D(internalFormat, size, size, 1);
  glTextureSubImage2D(texture.id(), 0, 0, 0, size, size, format, GL_FLOAT, texels);
  texture.parameter(GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  texture.parameter(GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  texture.parameter(GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  texture.parameter(GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return texture;
}

Texture Texture::ofBuffer(const Buffer& buffer, GLenum internalFormat) {
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_BUFFER, 1, &id);
  glTextureBuffer(id, internalFormat, buffer.id());
  return adopt(id, 0, 0);
}

void Texture::uploadRgba8(const void* pixels) const {
  glTextureSubImage2D(id(), 0, 0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
}

Renderbuffer Renderbuffer::create(GLenum format, int width, int height, int samples) {
  GLuint id = 0;
  glCreateRenderbuffers(1, &id);
  if (samples > 1) {
    glNamedRenderbufferStorageMultisample(id, samples, format, width, height);
  } else {
    glNamedRenderbufferStorage(id, format, width, height);
  }
  return Renderbuffer(id);
}

Query Query::create(GLenum target) {
  GLuint id = 0;
  glCreateQueries(target, 1, &id);
  return Query(id, target);
}

GLuint64 Query::result() const {
  GLuint64 value = 0;
  glGetQueryObjectui64v(id(), GL_QUERY_RESULT, &value);
  return value;
}

bool Query::available() const {
  GLuint ready = GL_FALSE;
  glGetQueryObjectuiv(id(), GL_QUERY_RESULT_AVAILABLE, &ready);
  return ready == GL_TRUE;
}

Framebuffer Framebuffer::create() {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  return Framebuffer(id);
}

void Framebuffer::attach(GLenum attachment, const Texture& texture, int level) const {
  glNamedFramebufferTexture(id(), attachment, texture.id(), level);
}

void Framebuffer::attach(GLenum attachment, const Renderbuffer& renderbuffer) const {
  glNamedFramebufferRenderbuffer(id(), attachment, GL_RENDERBUFFER, renderbuffer.id());
}

namespace {

const char* framebufferStatusName(GLenum status) {
  switch (status) {
    case GL_FRAMEBUFFER_UNDEFINED: return "GL_FRAMEBUFFER_UNDEFINED";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER: return "GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER";
    case GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER: return "GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER";
    case GL_FRAMEBUFFER_UNSUPPORTED: return "GL_FRAMEBUFFER_UNSUPPORTED";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE: return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS: return "GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS";
    default: return "unknown status";
  }
}

}  // namespace

Status Framebuffer::check(std::string_view name) const {
  GLenum status = 0;
  if (complete(&status)) return Ok{};
  char code[16];
  std::snprintf(code, sizeof code, "0x%04X", unsigned(status));
  return makeError("framebuffer \"" + std::string(name) + "\" is incomplete: " + framebufferStatusName(status) +
                   " (" + code + ")");
}

bool Framebuffer::complete(GLenum* status) const {
  const GLenum s = glCheckNamedFramebufferStatus(id(), GL_FRAMEBUFFER);
  if (status) *status = s;
  return s == GL_FRAMEBUFFER_COMPLETE;
}

namespace {

GLint attachmentParameter(GLuint framebuffer, GLenum attachment, GLenum name) {
  GLint value = 0;
  glGetNamedFramebufferAttachmentParameteriv(framebuffer, attachment, name, &value);
  return value;
}

// The width and height of the image attached at `attachment` (level 0 or the
// attached level of a texture).
glm::ivec2 attachmentSize(GLuint framebuffer, GLenum attachment) {
  const GLint type = attachmentParameter(framebuffer, attachment, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE);
  const auto object = GLuint(attachmentParameter(framebuffer, attachment, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME));
  glm::ivec2 size(0);
  if (type == GL_RENDERBUFFER) {
    glGetNamedRenderbufferParameteriv(object, GL_RENDERBUFFER_WIDTH, &size.x);
    glGetNamedRenderbufferParameteriv(object, GL_RENDERBUFFER_HEIGHT, &size.y);
  } else if (type == GL_TEXTURE) {
    const GLint level = attachmentParameter(framebuffer, attachment, GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL);
    glGetTextureLevelParameteriv(object, level, GL_TEXTURE_WIDTH, &size.x);
    glGetTextureLevelParameteriv(object, level, GL_TEXTURE_HEIGHT, &size.y);
  }
  return size;
}

// Colour attachment 0's object, when it is one another framebuffer can attach as
// it is: a renderbuffer or a 2D texture's level (not a cube face or a layer).
void shareableColor(GLuint framebuffer, FramebufferLayout& l) {
  const auto type = GLenum(attachmentParameter(framebuffer, GL_COLOR_ATTACHMENT0, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE));
  const auto object = GLuint(attachmentParameter(framebuffer, GL_COLOR_ATTACHMENT0, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME));
  if (type == GL_TEXTURE) {
    GLint target = 0;
    glGetTextureParameteriv(object, GL_TEXTURE_TARGET, &target);
    if (target != GL_TEXTURE_2D) return;
    l.colorLevel = attachmentParameter(framebuffer, GL_COLOR_ATTACHMENT0, GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL);
  } else if (type != GL_RENDERBUFFER) {
    return;
  }
  l.colorObjectType = type;
  l.colorObject = object;
}

}  // namespace

FramebufferLayout framebufferLayout(GLuint framebuffer) {
  FramebufferLayout l;
  if (framebuffer == 0) return l;
  glGetNamedFramebufferParameteriv(framebuffer, GL_SAMPLES, &l.samples);
  if (attachmentParameter(framebuffer, GL_COLOR_ATTACHMENT0, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE) != GL_NONE) {
    const glm::ivec2 size = attachmentSize(framebuffer, GL_COLOR_ATTACHMENT0);
    l.width = size.x;
    l.height = size.y;
    const GLenum bits[4] = {GL_FRAMEBUFFER_ATTACHMENT_RED_SIZE, GL_FRAMEBUFFER_ATTACHMENT_GREEN_SIZE,
                            GL_FRAMEBUFFER_ATTACHMENT_BLUE_SIZE, GL_FRAMEBUFFER_ATTACHMENT_ALPHA_SIZE};
    for (int c = 0; c < 4; ++c) l.colorBits[c] = attachmentParameter(framebuffer, GL_COLOR_ATTACHMENT0, bits[c]);
    l.colorType = GLenum(attachmentParameter(framebuffer, GL_COLOR_ATTACHMENT0, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE));
    shareableColor(framebuffer, l);
  }
  if (attachmentParameter(framebuffer, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE) != GL_NONE) {
    l.depthBits = attachmentParameter(framebuffer, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE);
    l.depthType = GLenum(attachmentParameter(framebuffer, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE));
  }
  return l;
}

}  // namespace engine::gl
