#include "render/kernel_shader_defines.h"

#include "core/rbf/kernels.h"

namespace hermite::render {

std::string kernelShaderDefines() {
  std::string defines;
  for (const KernelInfo& k : kKernelTable)
    defines += "#define " + std::string(k.shaderMacro) + " " + std::to_string(k.id) + "\n";
  return defines;
}

}  // namespace hermite::render
