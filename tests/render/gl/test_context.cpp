#include <doctest/doctest.h>

#include <chrono>
#include <cstdlib>

#include "core/base/errors.h"
#include "render/gl/context.h"
#include "render/gl/gl_objects.h"
#include "support/render_test_support.h"

using namespace hermite;
using namespace hermite::render;

namespace {

void checkCore45(RenderContext& context, const char* expected_name) {
  CHECK(context.name() == expected_name);
  GLint major = 0;
  GLint minor = 0;
  GLint profile = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  CHECK((major > 4 || (major == 4 && minor >= 5)));
  CHECK((profile & GL_CONTEXT_CORE_PROFILE_BIT) != 0);
  CHECK(GLAD_GL_VERSION_4_5 != 0);
  const bool dsa_loaded = glad_glCreateFramebuffers != nullptr;
  CHECK(dsa_loaded);
  CHECK(context.description().find("4.") == 0);
  CHECK_NOTHROW(checkGl("context creation"));
}

}  // namespace

TEST_CASE("osmesa gives an OpenGL 4.5 core context and glad loads it") {
  const auto start = std::chrono::steady_clock::now();
  auto context = testing::makeTestContext("osmesa");
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  MESSAGE("osmesa: " << context->description() << ", created in " << ms << " ms");
  checkCore45(*context, "osmesa");
  CHECK(context->framebufferSize().width == 64);
  CHECK(context->window() == nullptr);
  CHECK_NOTHROW(context->present());
}

TEST_CASE("egl surfaceless gives an OpenGL 4.5 core context and glad loads it") {
  if (testing::skipEgl()) {
    MESSAGE("HERMITE_SKIP_EGL=1: EGL test skipped");
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  auto context = testing::makeTestContext("egl");
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  MESSAGE("egl: " << context->description() << ", created in " << ms << " ms");
  checkCore45(*context, "egl");
}

TEST_CASE("switching between osmesa and egl contexts reloads the entry points") {
  if (testing::skipEgl()) return;
  auto osmesa = testing::makeTestContext("osmesa");
  auto egl = testing::makeTestContext("egl");
  for (int round = 0; round < 2; ++round) {
    for (RenderContext* context : {osmesa.get(), egl.get()}) {
      context->makeCurrent();
      Buffer buffer;
      const int value = 1234 + round;
      buffer.setData(&value, sizeof value);
      int back = 0;
      glGetNamedBufferSubData(buffer.id(), 0, sizeof back, &back);
      CHECK(back == value);
      CHECK_NOTHROW(checkGl("round trip"));
    }
  }
  osmesa->makeCurrent();
}

TEST_CASE("an unknown context name is a usage error") {
  CHECK_THROWS_AS(createContext("vulkan"), UsageError);
}

TEST_CASE("glfw without a display is an environment error") {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((display != nullptr && *display != '\0') || (wayland != nullptr && *wayland != '\0')) {
    MESSAGE("a display exists: the no-display case is not tested here");
    return;
  }
  try {
    auto context = createContext("glfw");
    FAIL("a GLFW window was created without a display");
  } catch (const EnvironmentError& error) {
    CHECK(std::string(error.what()).find("display") != std::string::npos);
  }
}
