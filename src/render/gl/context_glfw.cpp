// GLFW window with an OpenGL 4.5 core context, for the GUI.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <mutex>
#include <string>

#include "core/base/errors.h"
#include "render/gl/context.h"

namespace hermite::render {

namespace {

void* glfwProc(const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); }

// The last GLFW error of this thread: GLFW reports errors through a callback only.
thread_local std::string t_last_error;
void onGlfwError(int code, const char* description) {
  t_last_error = std::string(description != nullptr ? description : "?") + " (GLFW error " +
                 std::to_string(code) + ")";
}

// glfwInit/glfwTerminate are process-wide: count windows.
std::mutex g_glfw_mutex;
int g_glfw_users = 0;

void acquireGlfw() {
  const std::lock_guard lock(g_glfw_mutex);
  if (g_glfw_users == 0) {
    glfwSetErrorCallback(&onGlfwError);
    const char* x11 = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    const bool no_display = (x11 == nullptr || *x11 == '\0') && (wayland == nullptr || *wayland == '\0');
    t_last_error.clear();
    if (!glfwInit()) {
      throw EnvironmentError(std::string("glfw: cannot open a window: ") +
                             (no_display ? "no display (DISPLAY is not set); use --backend osmesa or egl"
                                         : t_last_error));
    }
  }
  ++g_glfw_users;
}

void releaseGlfw() {
  const std::lock_guard lock(g_glfw_mutex);
  if (--g_glfw_users == 0) glfwTerminate();
}

class GlfwContext final : public RenderContext {
 public:
  explicit GlfwContext(const ContextOptions& options) {
    acquireGlfw();
    try {
      glfwDefaultWindowHints();
      glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
      glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
      glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
      glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
      glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
      glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
      glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
      glfwWindowHint(GLFW_DEPTH_BITS, 24);
      t_last_error.clear();
      window_ = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
      if (window_ == nullptr) {
        throw EnvironmentError("glfw: could not create a window with an OpenGL 4.5 core context: " + t_last_error);
      }
      makeCurrentNative();
      glfwSwapInterval(options.vsync ? 1 : 0);
      finishCreation();
    } catch (...) {
      if (window_ != nullptr) glfwDestroyWindow(window_);
      releaseGlfw();
      throw;
    }
  }

  ~GlfwContext() override {
    glfwDestroyWindow(window_);
    releaseGlfw();
  }

  FramebufferSize framebufferSize() const override {
    FramebufferSize size;
    glfwGetFramebufferSize(window_, &size.width, &size.height);
    return size;
  }
  void present() override { glfwSwapBuffers(window_); }
  std::string_view name() const override { return "glfw"; }
  GlProcLoader procLoader() const override { return &glfwProc; }
  GLFWwindow* window() const override { return window_; }

 protected:
  void makeCurrentNative() override { glfwMakeContextCurrent(window_); }

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace

std::unique_ptr<RenderContext> createGlfwContext(const ContextOptions& options) {
  return std::make_unique<GlfwContext>(options);
}

}  // namespace hermite::render
