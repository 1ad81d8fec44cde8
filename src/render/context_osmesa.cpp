// OSMesa offscreen context. <GL/osmesa.h> pulls in <GL/gl.h>, so this file sees no glad header:
// it only hands OSMesaGetProcAddress to the loader.
#include <GL/osmesa.h>

#include <array>
#include <vector>

#include "core/errors.h"
#include "render/context.h"

namespace hermite::render {

namespace {

void* osmesaProc(const char* name) { return reinterpret_cast<void*>(OSMesaGetProcAddress(name)); }

class OsmesaContext final : public RenderContext {
 public:
  explicit OsmesaContext(const ContextOptions& options) : size_{options.width, options.height} {
    // Depth/stencil of OSMesa's own buffer are not needed: drawing goes into framebuffer objects.
    const std::array<int, 15> attribs = {OSMESA_FORMAT, OSMESA_RGBA,
                                         OSMESA_DEPTH_BITS, 0,
                                         OSMESA_STENCIL_BITS, 0,
                                         OSMESA_ACCUM_BITS, 0,
                                         OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                                         OSMESA_CONTEXT_MAJOR_VERSION, 4,
                                         OSMESA_CONTEXT_MINOR_VERSION, 5,
                                         0};
    context_ = OSMesaCreateContextAttribs(attribs.data(), nullptr);
    if (context_ == nullptr) {
      throw EnvironmentError("osmesa: could not create an OpenGL 4.5 core context (OSMesaCreateContextAttribs failed)");
    }
    try {
      makeCurrentNative();
      finishCreation();
    } catch (...) {
      OSMesaDestroyContext(context_);
      throw;
    }
  }

  ~OsmesaContext() override {
    if (OSMesaGetCurrentContext() == context_) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    OSMesaDestroyContext(context_);
  }

  FramebufferSize framebufferSize() const override { return size_; }
  void present() override {
    using FinishFn = void (*)();
    static const auto finish = reinterpret_cast<FinishFn>(OSMesaGetProcAddress("glFinish"));
    finish();
  }
  std::string_view name() const override { return "osmesa"; }
  GlProcLoader procLoader() const override { return &osmesaProc; }

 protected:
  void makeCurrentNative() override {
    // A 1x1 colour buffer makes the context current; the default framebuffer is not drawn to.
    if (!OSMesaMakeCurrent(context_, pixel_.data(), GL_UNSIGNED_BYTE, 1, 1)) {
      throw EnvironmentError("osmesa: OSMesaMakeCurrent failed");
    }
  }

 private:
  OSMesaContext context_ = nullptr;
  std::array<unsigned char, 4> pixel_{};
  FramebufferSize size_;
};

}  // namespace

std::unique_ptr<RenderContext> createOsmesaContext(const ContextOptions& options) {
  return std::make_unique<OsmesaContext>(options);
}

}  // namespace hermite::render
