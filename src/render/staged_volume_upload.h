#pragma once
// The GL half of a tracer upload spread over several calls: the textures of a TracerVolume
// (implicit_tracer.h) are created first and then filled slab by slab of z-slices, each call
// stopping once its time budget is spent. The window uploads a 128³ bake (8 MB of R32F values and
// 8 MB of RGBA8 normals) this way over several frames while it keeps tracing the previous bake;
// the tracer switches to the new textures once every texel is on the GPU
// (ImplicitTracer::beginUpload / continueUpload). Every call must happen on the GL thread.

#include "render/gl/gl_objects.h"
#include "render/implicit_tracer.h"

namespace hermite::render {

// The baked mode's textures of one upload.
struct VolumeTextures {
  Texture volume;       // R32F, R × R × R: f at the bake's samples
  Texture normals;      // RGBA8, R × R × R: unit directions (baked_normals.h)
  Texture bricks;       // RGBA32F per bake brick
  Texture bakedBricks;  // RGBA32F per brick of the baked march's own grid
};

class StagedVolumeUpload {
 public:
  // Creates the (empty) textures for `volume`, which must hold a bake. Throws InputError otherwise.
  explicit StagedVolumeUpload(TracerVolume volume);

  // Copies the next slabs (kSlabSlices z-slices of the bake and of its normals; the brick
  // textures in one last step) until `budgetMs` of wall clock went by, at least one step;
  // infinity copies all that is left, each texture in one call. True once all is on the GPU.
  bool copy(double budgetMs);
  bool done() const { return nextSlice_ >= resolution() && bricksDone_; }
  // Wall clock spent in copy() so far.
  double copyMs() const { return copyMs_; }

  TracerVolume& volume() { return volume_; }
  VolumeTextures& textures() { return textures_; }

  // z-slices per step: 8 slices of a 128³ bake are 1 MB of texels (values and normals).
  static constexpr int kSlabSlices = 8;

 private:
  int resolution() const { return volume_.bake->resolution; }
  void copySlices(int z0, int z1);
  void copyBricks();

  TracerVolume volume_;
  VolumeTextures textures_;
  int nextSlice_ = 0;  // z-slices [0, nextSlice_) are copied
  bool bricksDone_ = false;
  double copyMs_ = 0;
};

}  // namespace hermite::render
