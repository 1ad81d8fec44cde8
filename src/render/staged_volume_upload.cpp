#include "render/staged_volume_upload.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/base/errors.h"
#include "core/base/ms_since.h"
#include "render/gl/gl_loader.h"

namespace hermite::render {

StagedVolumeUpload::StagedVolumeUpload(TracerVolume volume) : volume_(std::move(volume)) {
  if (!volume_.bake) throw InputError("implicit tracer: upload of an empty volume");
  const int R = resolution();
  textures_.volume = Texture::create3D(GL_R32F, R, R, R);
  textures_.volume.setFilter(GL_LINEAR, GL_LINEAR);
  textures_.volume.setWrap(GL_CLAMP_TO_EDGE);
  textures_.normals = Texture::create3D(GL_RGBA8, R, R, R);
  textures_.normals.setFilter(GL_LINEAR, GL_LINEAR);
  textures_.normals.setWrap(GL_CLAMP_TO_EDGE);
  const Eigen::Array3i count = volume_.bake->bricks.count;
  textures_.bricks = Texture::create3D(GL_RGBA32F, count.x(), count.y(), count.z());
  textures_.bricks.setFilter(GL_NEAREST, GL_NEAREST);
  const Eigen::Array3i& bc = volume_.bakedBrickCount;
  textures_.bakedBricks = Texture::create3D(GL_RGBA32F, bc.x(), bc.y(), bc.z());
  textures_.bakedBricks.setFilter(GL_NEAREST, GL_NEAREST);
}

// z-slices [z0, z1) of the bake's values and normals (the bake is x-fastest, then y, then z).
void StagedVolumeUpload::copySlices(int z0, int z1) {
  const int R = resolution();
  const std::size_t first = std::size_t(z0) * std::size_t(R) * std::size_t(R);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage3D(textures_.volume.id(), 0, 0, 0, z0, R, R, z1 - z0, GL_RED, GL_FLOAT,
                      volume_.bake->values.data() + first);
  glTextureSubImage3D(textures_.normals.id(), 0, 0, 0, z0, R, R, z1 - z0, GL_RGBA, GL_UNSIGNED_BYTE,
                      volume_.normalTexels.data() + 4 * first);
  checkGl("implicit tracer volume upload");
}

void StagedVolumeUpload::copyBricks() {
  textures_.bricks.upload3D(GL_RGBA, GL_FLOAT, volume_.brickTexels.data());
  textures_.bakedBricks.upload3D(GL_RGBA, GL_FLOAT, volume_.bakedBrickTexels.data());
  bricksDone_ = true;
}

bool StagedVolumeUpload::copy(double budgetMs) {
  const auto t0 = std::chrono::steady_clock::now();
  const int R = resolution();
  if (!std::isfinite(budgetMs)) {
    if (nextSlice_ < R) copySlices(nextSlice_, R);
    nextSlice_ = R;
  }
  while (!done()) {
    if (nextSlice_ < R) {
      const int z1 = std::min(R, nextSlice_ + kSlabSlices);
      copySlices(nextSlice_, z1);
      nextSlice_ = z1;
    } else {
      copyBricks();
    }
    if (msSince(t0) >= budgetMs) break;
  }
  copyMs_ += msSince(t0);
  return done();
}

}  // namespace hermite::render
