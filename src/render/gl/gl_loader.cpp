#include "render/gl/gl_loader.h"

#include <glad/gl.h>

#include "core/base/errors.h"

namespace hermite::render {

namespace {
GlProcLoader g_loader = nullptr;
GLADapiproc trampoline(const char* name) {
  return reinterpret_cast<GLADapiproc>(g_loader(name));
}
}  // namespace

GlVersion loadGl(GlProcLoader loader) {
  if (loader == nullptr) throw EnvironmentError("no GL get-proc-address function");
  g_loader = loader;
  const int version = gladLoadGL(trampoline);
  if (version == 0) throw EnvironmentError("could not load OpenGL entry points (no current context?)");
  GlVersion v{GLAD_VERSION_MAJOR(version), GLAD_VERSION_MINOR(version)};
  if (v.major < 4 || (v.major == 4 && v.minor < 5)) {
    throw EnvironmentError("OpenGL 4.5 core is required, the context offers " +
                           std::to_string(v.major) + "." + std::to_string(v.minor));
  }
  return v;
}

std::string describeCurrentContext() {
  auto str = [](GLenum e) {
    const GLubyte* s = glGetString(e);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return str(GL_VERSION) + " (" + str(GL_VENDOR) + ", " + str(GL_RENDERER) + ")";
}

bool isMesaSoftwareRenderer() {
  const GLubyte* renderer = glGetString(GL_RENDERER);
  if (renderer == nullptr) return false;
  const std::string name(reinterpret_cast<const char*>(renderer));
  return name.find("llvmpipe") != std::string::npos || name.find("softpipe") != std::string::npos;
}

}  // namespace hermite::render
