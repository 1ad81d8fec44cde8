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

// True when the current context is Mesa's llvmpipe or softpipe (GL_RENDERER). Their shaders stop
// every loop once 65 535 loop iterations have run in one invocation (kMesaSoftwareLoopLimit):
// shaders with long nested loops must budget for it.
bool isMesaSoftwareRenderer();
constexpr int kMesaSoftwareLoopLimit = 65535;

}  // namespace hermite::render
