// OSMesa: Mesa's software renderer with a plain memory buffer as the default
// framebuffer. We render into our own FBOs, so the buffer only needs to exist.
#include <GL/osmesa.h>

#include <vector>

#include "platform/gl_context_impl.h"

namespace engine {
namespace {

void* osmesaProc(const char* name) { return reinterpret_cast<void*>(OSMesaGetProcAddress(name)); }

class OsMesaContext final : public BackendContext {
 public:
  ~OsMesaContext() override {
    if (context_) OSMesaDestroyContext(context_);
  }
  Backend backend() const override { return Backend::OsMesa; }
  void makeCurrent() override {
    OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_);
  }

  Status init(const ContextOptions& options) {
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    context_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!context_) {
      return makeError("OSMesa: cannot create an OpenGL 4.5 core context; is libosmesa6 "
                       "installed? try --offscreen=egl");
    }
    width_ = options.width;
    height_ = options.height;
    buffer_.assign(static_cast<size_t>(width_) * height_ * 4, 0);
    if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_)) {
      return makeError("OSMesa: cannot make the context current");
    }
    return loadGl(osmesaProc, "OSMesa");
  }

 private:
  OSMesaContext context_ = nullptr;
  std::vector<unsigned char> buffer_;
  int width_ = 0;
  int height_ = 0;
};

}  // namespace

Result<std::unique_ptr<GlContext>> createOsMesaContext(const ContextOptions& options) {
  auto context = std::make_unique<OsMesaContext>();
  if (auto status = context->init(options); !status) return status.error();
  return std::unique_ptr<GlContext>(std::move(context));
}

}  // namespace engine
