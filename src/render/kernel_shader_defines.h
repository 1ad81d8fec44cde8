#pragma once
// The kernel ids as GLSL macros, from the one kernel table (core/rbf/kernels.h): the trace
// shaders compare the uniform uKernel with KERNEL_GAUSSIAN, KERNEL_WENDLAND, … instead of bare
// integers.

#include <string>

namespace hermite::render {

// "#define KERNEL_GAUSSIAN 0\n#define KERNEL_WENDLAND 1\n…", one line per row of kKernelTable.
std::string kernelShaderDefines();

}  // namespace hermite::render
