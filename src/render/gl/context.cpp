#include "render/gl/context.h"

#include <glad/gl.h>

#include "core/base/errors.h"
#include "render/gl/gl_objects.h"

namespace hermite::render {

namespace {
// The loader glad's function pointers currently come from. OSMesa hands out driver functions
// directly, EGL and GLFW dispatch stubs: switching between them needs a reload.
thread_local GlProcLoader t_loaded_from = nullptr;
}  // namespace

void RenderContext::makeCurrent() {
  makeCurrentNative();
  if (t_loaded_from != procLoader()) {
    loadGl(procLoader());
    t_loaded_from = procLoader();
  }
}

void RenderContext::finishCreation() {
  loadGl(procLoader());
  t_loaded_from = procLoader();
  GLint profile = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  if ((profile & GL_CONTEXT_CORE_PROFILE_BIT) == 0) {
    throw EnvironmentError(std::string(name()) + ": the context is not a core profile context: " +
                           describeCurrentContext());
  }
  if (glChecksEnabled()) installGlDebugOutput();
}

std::string RenderContext::description() {
  makeCurrent();
  return describeCurrentContext();
}

std::unique_ptr<RenderContext> createContext(std::string_view name, const ContextOptions& options) {
  if (name == "osmesa") return createOsmesaContext(options);
  if (name == "egl") return createEglContext(options);
  if (name == "glfw") return createGlfwContext(options);
  throw UsageError("unknown GL context '" + std::string(name) + "' (expected osmesa, egl or glfw)");
}

std::vector<std::string> contextNames() { return {"osmesa", "egl", "glfw"}; }

}  // namespace hermite::render
