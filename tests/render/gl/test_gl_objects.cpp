#include <doctest/doctest.h>

#include <string>
#include <utility>
#include <vector>

#include "core/base/errors.h"
#include "render/gl/gl_objects.h"
#include "support/render_test_support.h"

using namespace hermite;
using namespace hermite::render;

TEST_CASE("GL error checks throw an EnvironmentError when enabled, and only then") {
  auto context = testing::makeTestContext();
  REQUIRE(glChecksEnabled());
  glBindTexture(0x1234, 0);  // GL_INVALID_ENUM
  try {
    checkGl("a deliberate bad call");
    FAIL("no exception");
  } catch (const EnvironmentError& error) {
    const std::string message = error.what();
    CHECK(message.find("GL_INVALID_ENUM") != std::string::npos);
    CHECK(message.find("a deliberate bad call") != std::string::npos);
  }
  CHECK_NOTHROW(checkGl("after the error was consumed"));

  // A wrapper operation that fails reports it itself.
  CHECK_THROWS_AS(Texture::create2D(0x1234, 4, 4), EnvironmentError);
  CHECK_NOTHROW(checkGl("after the wrapper error"));

  setGlChecks(false);
  glBindTexture(0x1234, 0);
  CHECK_NOTHROW(checkGl("checks off"));
  setGlChecks(true);
  clearGlErrors();
  CHECK_NOTHROW(checkGl("after clearGlErrors"));
}

TEST_CASE("Buffer round trip and move semantics") {
  auto context = testing::makeTestContext();
  const std::vector<float> values = {1.0f, 2.5f, -3.0f};
  Buffer a;
  a.setData(std::span<const float>(values));
  CHECK(a.size() == 3 * sizeof(float));
  const GLuint id = a.id();
  Buffer b = std::move(a);
  CHECK(a.id() == 0);
  CHECK(b.id() == id);
  std::vector<float> back(3);
  glGetNamedBufferSubData(b.id(), 0, static_cast<GLsizeiptr>(b.size()), back.data());
  CHECK(back == values);
  CHECK(glIsBuffer(id) == GL_TRUE);
  {
    Buffer c = std::move(b);
  }
  CHECK(glIsBuffer(id) == GL_FALSE);
}

TEST_CASE("R32F 3D textures keep float values exactly") {
  auto context = testing::makeTestContext();
  const int nx = 5, ny = 4, nz = 3;
  std::vector<float> voxels(static_cast<std::size_t>(nx * ny * nz));
  for (std::size_t i = 0; i < voxels.size(); ++i) voxels[i] = static_cast<float>(i) * 0.125f - 2.0f;
  Texture texture = Texture::create3D(GL_R32F, nx, ny, nz);
  texture.upload3D(GL_RED, GL_FLOAT, voxels.data());
  CHECK(texture.target() == GL_TEXTURE_3D);
  CHECK(texture.depth() == nz);
  std::vector<float> back(voxels.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(texture.id(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(back.size() * sizeof(float)), back.data());
  CHECK(back == voxels);
}

TEST_CASE("Framebuffer with colour and depth attachments is complete") {
  auto context = testing::makeTestContext();
  Framebuffer framebuffer(7, 5, true);
  CHECK_NOTHROW(framebuffer.checkComplete());
  CHECK(framebuffer.color().internalFormat() == GL_RGBA8);
  CHECK(framebuffer.depth().internalFormat() == GL_DEPTH_COMPONENT24);
  framebuffer.bind();
  GLint viewport[4] = {};
  glGetIntegerv(GL_VIEWPORT, viewport);
  CHECK(viewport[2] == 7);
  CHECK(viewport[3] == 5);
  Framebuffer moved = std::move(framebuffer);
  CHECK(framebuffer.id() == 0);
  CHECK(moved.width() == 7);
}
