#pragma once
// Shared set-up of the render tests: a small context with GL error checks on.

#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

#include "render/gl/context.h"
#include "render/gl/gl_objects.h"

namespace hermite::render::testing {

inline std::unique_ptr<RenderContext> makeTestContext(const std::string& name = "osmesa") {
  setGlChecks(true);
  ContextOptions options;
  options.width = 64;
  options.height = 64;
  options.debug = true;
  return createContext(name, options);
}

// EGL surfaceless works with Mesa's llvmpipe, which every supported machine has; only an explicit
// opt-out (HERMITE_SKIP_EGL) skips it.
inline bool skipEgl() {
  const char* value = std::getenv("HERMITE_SKIP_EGL");
  return value != nullptr && std::strcmp(value, "1") == 0;
}

}  // namespace hermite::render::testing
