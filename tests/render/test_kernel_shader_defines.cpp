// The shaders take the kernel ids from the one kernel table: every row is defined with its id,
// and the exact trace shader names each kernel by its macro, never by a bare integer.

#include <doctest/doctest.h>

#include <regex>
#include <string>

#include "core/rbf/kernels.h"
#include "render/gl/shader_library.h"
#include "render/kernel_shader_defines.h"

using namespace hermite;
using namespace hermite::render;

TEST_CASE("kernel shader defines: one #define per table row, with the row's id") {
  const std::string defines = kernelShaderDefines();
  for (const KernelInfo& k : kKernelTable) {
    CAPTURE(k.name);
    CHECK(defines.find("#define " + std::string(k.shaderMacro) + " " + std::to_string(k.id) + "\n") !=
          std::string::npos);
    CHECK(kernelInfo(k.type).id == k.id);
    CHECK(kernelName(k.type) == k.name);
  }
}

TEST_CASE("the exact trace shader compares uKernel with the table's macros only") {
  const std::string source(shaderSource("trace_exact.frag"));
  for (const KernelInfo& k : kKernelTable) {
    CAPTURE(k.shaderMacro);
    CHECK(source.find("uKernel == " + std::string(k.shaderMacro)) != std::string::npos);
  }
  CHECK_FALSE(std::regex_search(source, std::regex(R"(uKernel\s*[=!]=\s*[0-9])")));
}
