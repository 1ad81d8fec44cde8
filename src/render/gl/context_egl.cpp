// EGL surfaceless context: no window system, no surface; drawing goes into framebuffer objects.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstring>
#include <map>
#include <mutex>
#include <string>

#include "core/base/errors.h"
#include "render/gl/context.h"

namespace hermite::render {

namespace {

void* eglProc(const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); }

std::string eglErrorName(EGLint code) {
  switch (code) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: {
      char buffer[16];
      std::snprintf(buffer, sizeof buffer, "0x%04x", static_cast<unsigned>(code));
      return buffer;
    }
  }
}

bool hasExtension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + n, name)) {
    const bool starts = p == list || p[-1] == ' ';
    const bool ends = p[n] == '\0' || p[n] == ' ';
    if (starts && ends) return true;
  }
  return false;
}

// The surfaceless Mesa platform when the client offers it, else the default display (NVIDIA's
// EGL gives a device-backed default display that supports surfaceless contexts too).
EGLDisplay openDisplay(std::string& how) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (hasExtension(client, "EGL_MESA_platform_surfaceless")) {
    using GetPlatformDisplay = PFNEGLGETPLATFORMDISPLAYEXTPROC;
    const auto get = reinterpret_cast<GetPlatformDisplay>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get != nullptr) {
      EGLDisplay display = get(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      if (display != EGL_NO_DISPLAY) {
        how = "EGL_PLATFORM_SURFACELESS_MESA";
        return display;
      }
    }
  }
  how = "EGL_DEFAULT_DISPLAY";
  return eglGetDisplay(EGL_DEFAULT_DISPLAY);
}

// EGL displays are per-process singletons and eglTerminate ends every context on one: count users.
std::mutex g_display_mutex;
std::map<EGLDisplay, int> g_display_users;

bool initializeDisplay(EGLDisplay display) {
  const std::lock_guard lock(g_display_mutex);
  EGLint major = 0;
  EGLint minor = 0;
  if (g_display_users[display] == 0 && !eglInitialize(display, &major, &minor)) return false;
  ++g_display_users[display];
  return true;
}

void releaseDisplay(EGLDisplay display) {
  const std::lock_guard lock(g_display_mutex);
  if (--g_display_users[display] == 0) eglTerminate(display);
}

class EglContext final : public RenderContext {
 public:
  explicit EglContext(const ContextOptions& options) : size_{options.width, options.height} {
    std::string how;
    display_ = openDisplay(how);
    if (display_ == EGL_NO_DISPLAY) throw EnvironmentError("egl: no EGL display (" + how + ")");
    if (!initializeDisplay(display_)) {
      throw EnvironmentError("egl: eglInitialize failed on " + how + ": " + eglErrorName(eglGetError()) +
                             " (no EGL device or driver?)");
    }
    try {
      create(options, how);
    } catch (...) {
      if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
      releaseDisplay(display_);
      throw;
    }
  }

  ~EglContext() override {
    if (eglGetCurrentContext() == context_) {
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    eglDestroyContext(display_, context_);
    releaseDisplay(display_);
  }

  FramebufferSize framebufferSize() const override { return size_; }
  void present() override {
    using FinishFn = void (*)();
    static const auto finish = reinterpret_cast<FinishFn>(eglGetProcAddress("glFinish"));
    finish();
  }
  std::string_view name() const override { return "egl"; }
  GlProcLoader procLoader() const override { return &eglProc; }

 protected:
  void makeCurrentNative() override {
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
      throw EnvironmentError("egl: eglMakeCurrent without a surface failed: " + eglErrorName(eglGetError()));
    }
  }

 private:
  void create(const ContextOptions& options, const std::string& how) {
    const char* extensions = eglQueryString(display_, EGL_EXTENSIONS);
    if (!hasExtension(extensions, "EGL_KHR_surfaceless_context")) {
      throw EnvironmentError("egl: the display (" + how + ") does not support EGL_KHR_surfaceless_context");
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
      throw EnvironmentError("egl: desktop OpenGL is not available (eglBindAPI failed: " +
                             eglErrorName(eglGetError()) + ")");
    }
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!hasExtension(extensions, "EGL_KHR_no_config_context") &&
        !hasExtension(extensions, "EGL_MESA_configless_context")) {
      const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                       EGL_NONE};
      EGLint count = 0;
      if (!eglChooseConfig(display_, config_attribs, &config, 1, &count) || count == 0) {
        throw EnvironmentError("egl: no config with desktop OpenGL on " + how);
      }
    }
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4,
                                      EGL_CONTEXT_MINOR_VERSION, 5,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_CONTEXT_OPENGL_DEBUG, options.debug ? EGL_TRUE : EGL_FALSE,
                                      EGL_NONE};
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, context_attribs);
    if (context_ == EGL_NO_CONTEXT) {
      throw EnvironmentError("egl: could not create an OpenGL 4.5 core context on " + how + ": " +
                             eglErrorName(eglGetError()));
    }
    makeCurrentNative();
    finishCreation();
  }

  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  FramebufferSize size_;
};

}  // namespace

std::unique_ptr<RenderContext> createEglContext(const ContextOptions& options) {
  return std::make_unique<EglContext>(options);
}

}  // namespace hermite::render
