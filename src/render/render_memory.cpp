#include "render/render_memory.h"

#include <string>

namespace hermite {

PlannedAllocation renderPlan(int width, int height) {
  const std::uint64_t w = width > 0 ? std::uint64_t(width) : 0, h = height > 0 ? std::uint64_t(height) : 0;
  return {saturatingSum({kRenderFixedBytes, saturatingProduct({w, h, kRenderBytesPerPixel})}),
          "rendering " + std::to_string(width) + " x " + std::to_string(height) + " pixels (about " +
              std::to_string(kRenderBytesPerPixel) + " bytes each)"};
}

}  // namespace hermite
