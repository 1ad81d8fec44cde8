// OSMesa offscreen context. <GL/osmesa.h> pulls in <GL/gl.h>, so this file sees no glad header:
// it only hands OSMesaGetProcAddress to the loader.
//
// libOSMesa is loaded with dlopen on first use rather than linked: it pulls in libLLVM, whose
// static initialisers cost every process start time (docs/performance.md), twice where
// blas_setup re-executes, although only the commands that draw need GL.
#include <GL/osmesa.h>
#include <dlfcn.h>

#include <array>
#include <string>
#include <type_traits>
#include <vector>

#include "core/base/errors.h"
#include "render/gl/context.h"

namespace hermite::render {

namespace {

// The OSMesa entry points this file uses, resolved from the shared library at run time.
struct OsmesaApi {
  decltype(&::OSMesaCreateContextAttribs) createContextAttribs = nullptr;
  decltype(&::OSMesaDestroyContext) destroyContext = nullptr;
  decltype(&::OSMesaMakeCurrent) makeCurrent = nullptr;
  decltype(&::OSMesaGetCurrentContext) getCurrentContext = nullptr;
  decltype(&::OSMesaGetProcAddress) getProcAddress = nullptr;
};

const OsmesaApi& osmesa() {
  static const OsmesaApi api = [] {
    void* lib = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
    if (lib == nullptr) lib = dlopen("libOSMesa.so", RTLD_NOW | RTLD_LOCAL);
    if (lib == nullptr) {
      const char* why = dlerror();
      throw EnvironmentError(std::string("osmesa: cannot load libOSMesa.so.8 (install libosmesa6): ") +
                             (why ? why : "unknown error"));
    }
    OsmesaApi a;
    auto load = [&](auto& fn, const char* name) {
      fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(dlsym(lib, name));
      if (fn == nullptr) throw EnvironmentError(std::string("osmesa: libOSMesa has no ") + name);
    };
    load(a.createContextAttribs, "OSMesaCreateContextAttribs");
    load(a.destroyContext, "OSMesaDestroyContext");
    load(a.makeCurrent, "OSMesaMakeCurrent");
    load(a.getCurrentContext, "OSMesaGetCurrentContext");
    load(a.getProcAddress, "OSMesaGetProcAddress");
    return a;
  }();
  return api;
}

void* osmesaProc(const char* name) { return reinterpret_cast<void*>(osmesa().getProcAddress(name)); }

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
    context_ = osmesa().createContextAttribs(attribs.data(), nullptr);
    if (context_ == nullptr) {
      throw EnvironmentError("osmesa: could not create an OpenGL 4.5 core context (OSMesaCreateContextAttribs failed)");
    }
    try {
      makeCurrentNative();
      finishCreation();
    } catch (...) {
      osmesa().destroyContext(context_);
      throw;
    }
  }

  ~OsmesaContext() override {
    if (osmesa().getCurrentContext() == context_) osmesa().makeCurrent(nullptr, nullptr, 0, 0, 0);
    osmesa().destroyContext(context_);
  }

  FramebufferSize framebufferSize() const override { return size_; }
  void present() override {
    using FinishFn = void (*)();
    static const auto finish = reinterpret_cast<FinishFn>(osmesa().getProcAddress("glFinish"));
    finish();
  }
  std::string_view name() const override { return "osmesa"; }
  GlProcLoader procLoader() const override { return &osmesaProc; }

 protected:
  void makeCurrentNative() override {
    // A 1x1 colour buffer makes the context current; the default framebuffer is not drawn to.
    if (!osmesa().makeCurrent(context_, pixel_.data(), GL_UNSIGNED_BYTE, 1, 1)) {
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
