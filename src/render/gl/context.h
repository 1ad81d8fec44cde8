#pragma once
// OpenGL 4.5 core contexts behind one interface, chosen by name:
//   "osmesa"  offscreen through Mesa's OSMesa (no display, no GPU; the headless default),
//   "egl"     EGL surfaceless (llvmpipe here, the real driver on GPU machines),
//   "glfw"    a window for the GUI (needs a display).
// Offscreen contexts have no usable default framebuffer: draw into an OffscreenTarget.
// Creation makes the context current and loads the GL entry points through glad; every failure
// (no display, no EGL device, context refused) is a hermite::EnvironmentError (exit code 4).

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "render/gl/gl_loader.h"

struct GLFWwindow;

namespace hermite::render {

struct ContextOptions {
  int width = 800;  // window size in screen units; offscreen contexts only report it
  int height = 600;
  std::string title = "Hermite Lab";
  bool visible = true;  // glfw: false creates a hidden window (tests)
  bool vsync = true;    // glfw: swap interval 1
  bool debug = false;   // request a debug context where the API allows it (egl, glfw)
};

struct FramebufferSize {
  int width = 0;  // pixels
  int height = 0;
};

class RenderContext {
 public:
  virtual ~RenderContext() = default;
  RenderContext(const RenderContext&) = delete;
  RenderContext& operator=(const RenderContext&) = delete;

  // Makes this context current on the calling thread and points glad at its entry points
  // (reloaded only when another context's loader was used last).
  void makeCurrent();

  // Window: the drawable size in pixels (differs from the window size on high-DPI screens).
  // Offscreen: the size given in ContextOptions.
  virtual FramebufferSize framebufferSize() const = 0;
  // Window: swaps buffers. Offscreen: glFinish, so timings include the GPU work.
  virtual void present() = 0;
  // "osmesa", "egl" or "glfw".
  virtual std::string_view name() const = 0;
  virtual GlProcLoader procLoader() const = 0;
  // The GLFW window of a "glfw" context (for input and the ImGui platform backend); else nullptr.
  virtual GLFWwindow* window() const { return nullptr; }

  // Version, vendor and renderer, e.g. "4.5 (Core Profile) Mesa 22.3.6 (Mesa, llvmpipe ...)".
  std::string description();

 protected:
  RenderContext() = default;
  virtual void makeCurrentNative() = 0;
  // Called by each backend's constructor once its context is current: loads glad, checks 4.5.
  void finishCreation();
};

// Creates the context named `name` ("osmesa", "egl", "glfw"), current on the calling thread.
// An unknown name is a hermite::UsageError; a context that cannot be created an EnvironmentError.
std::unique_ptr<RenderContext> createContext(std::string_view name, const ContextOptions& options = {});

// The names createContext accepts, headless ones first.
std::vector<std::string> contextNames();

// Backends (one file each).
std::unique_ptr<RenderContext> createOsmesaContext(const ContextOptions& options);
std::unique_ptr<RenderContext> createEglContext(const ContextOptions& options);
std::unique_ptr<RenderContext> createGlfwContext(const ContextOptions& options);

}  // namespace hermite::render
