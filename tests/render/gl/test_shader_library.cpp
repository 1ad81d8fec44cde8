#include <doctest/doctest.h>

#include <algorithm>
#include <string>

#include "core/base/errors.h"
#include "render/gl/shader_library.h"
#include "render/kernel_shader_defines.h"
#include "support/render_test_support.h"

using namespace hermite;
using namespace hermite::render;

namespace {

std::string compileError(const ShaderSource& source) {
  try {
    compileShader(source);
  } catch (const EnvironmentError& error) {
    return error.what();
  }
  return {};
}

}  // namespace

TEST_CASE("shaders from shaders/ are embedded into the binary") {
  const auto names = shaderNames();
  CHECK(std::find(names.begin(), names.end(), "fullscreen.vert") != names.end());
  CHECK(std::find(names.begin(), names.end(), "imgui.frag") != names.end());
  CHECK(shaderSource("fullscreen.vert").find("gl_VertexID") != std::string_view::npos);
  CHECK(shaderStageFor("fullscreen.vert") == GL_VERTEX_SHADER);
  CHECK(shaderStageFor("x.frag") == GL_FRAGMENT_SHADER);
  CHECK_THROWS_AS(shaderSource("missing.frag"), EnvironmentError);
  CHECK_THROWS_AS(shaderStageFor("missing.txt"), EnvironmentError);
}

TEST_CASE("a shader compile error names the file and the line") {
  auto context = testing::makeTestContext();

  SUBCASE("with its own #version") {
    const std::string source =
        "#version 450 core\n"
        "out vec4 color;\n"
        "void main() {\n"
        "  color = vec4(1.0);\n"
        "  color += undeclared_thing;\n"  // line 5
        "}\n";
    const std::string message = compileError({GL_FRAGMENT_SHADER, source, "broken.frag"});
    CAPTURE(message);
    CHECK(message.find("broken.frag:5") != std::string::npos);
    CHECK(message.find("undeclared_thing") != std::string::npos);
  }
  SUBCASE("with the prepended #version prelude") {
    const std::string source =
        "out vec4 color;\n"
        "void main() {\n"
        "  color = vec4(1.0) * missing_value;\n"  // line 3
        "}\n";
    const std::string message = compileError({GL_FRAGMENT_SHADER, source, "prelude.frag"});
    CAPTURE(message);
    CHECK(message.find("prelude.frag:3") != std::string::npos);
  }
  SUBCASE("after an #include, lines still count in the including file") {
    const std::string source =
        "#version 450 core\n"
        "out vec4 color;\n"
        "#include \"solid_color.frag\"\n"
        "void broken() {\n"
        "  int x = not_here;\n"  // line 5
        "}\n";
    // solid_color.frag has its own #version: included files may not.
    const std::string bad_include = compileError({GL_FRAGMENT_SHADER, source, "includer.frag"});
    CHECK(bad_include.find("#version in an included file") != std::string::npos);
  }
  SUBCASE("a missing #include names the including file and line") {
    const std::string source = "out vec4 color;\n#include \"nowhere.glsl\"\nvoid main() { color = vec4(1.0); }\n";
    const std::string message = compileError({GL_FRAGMENT_SHADER, source, "includer.frag"});
    CHECK(message.find("includer.frag:2") != std::string::npos);
    CHECK(message.find("nowhere.glsl") != std::string::npos);
  }
  SUBCASE("a link error names the files") {
    const std::string vert = "void main() { gl_Position = vec4(0.0); }\n";
    const std::string frag = "void helper();\nout vec4 c;\nvoid main() { helper(); c = vec4(1.0); }\n";
    try {
      buildProgram({ShaderSource{GL_VERTEX_SHADER, vert, "a.vert"}, ShaderSource{GL_FRAGMENT_SHADER, frag, "b.frag"}});
      FAIL("linked a program with an undefined function");
    } catch (const EnvironmentError& error) {
      const std::string message = error.what();
      CHECK(message.find("a.vert + b.frag") != std::string::npos);
    }
  }
}

TEST_CASE("driver logs of the common vendors are translated to FILE:LINE") {
  const std::vector<std::string> files = {"main.frag", "common.glsl"};
  CHECK(translateShaderLog("0:12(3): error: `x' undeclared", files) == "main.frag:12:3: error: `x' undeclared");
  CHECK(translateShaderLog("1(7) : error C1008: undefined variable \"y\"", files) ==
        "common.glsl:7: error C1008: undefined variable \"y\"");
  CHECK(translateShaderLog("ERROR: 0:4: 'z' : undeclared identifier", files) ==
        "main.frag:4: error: 'z' : undeclared identifier");
  CHECK(translateShaderLog("something else", files) == "something else");
}

TEST_CASE("every embedded shader compiles; those naming a kernel with the ids the tracer defines") {
  auto context = testing::makeTestContext();
  for (const std::string& name : shaderNames()) {
    CAPTURE(name);
    if (name.ends_with(".glsl")) continue;
    const std::string source(shaderSource(name));
    const std::string defines = source.find("KERNEL_") != std::string::npos ? kernelShaderDefines() : "";
    CHECK_NOTHROW(compileShader({shaderStageFor(name), defines + source, name}));
  }
}
