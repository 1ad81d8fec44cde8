#pragma once
// Loading OpenGL 4.5 core entry points through the generated glad loader.
// Every context (GLFW window, OSMesa, EGL) hands its own get-proc-address function here.

#include <string>

namespace hermite::render {

// Signature shared by glfwGetProcAddress, OSMesaGetProcAddress and eglGetProcAddress.
using GlProcLoader = void* (*)(const char* name);

struct GlVersion {
  int major = 0;
  int minor = 0;
};

// Loads all GL entry points of the current context. Returns the context's version;
// throws hermite::EnvironmentError when the context is older than 4.5 core or loading fails.
GlVersion loadGl(GlProcLoader loader);

// "4.5 (Mesa llvmpipe ...)": version, vendor and renderer of the current context, for logs.
std::string describeCurrentContext();

}  // namespace hermite::render
