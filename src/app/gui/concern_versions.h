#pragma once
// One version counter per concern of the document (docs/design.md, Data flow): each part of the
// window recomputes only what its own concerns made stale — the fit worker refits when what a
// fit reads changed (data and mode, fit settings, transform, patch, hole filling), the view
// image re-renders on a view change and re-traces on a camera move, and nothing refits for
// either.

#include <cstdint>

#include "scene/scene_file.h"

namespace hermite::app {

struct ConcernVersions {
  std::uint64_t data = 1;       // data source and samples, and the mode (what is fitted at all)
  std::uint64_t fit = 1;        // fit settings (method, kernel, r, partition, ...)
  std::uint64_t transform = 1;  // the similarity / matrix applied to the fitted model
  std::uint64_t patch = 1;      // the patch editor's document
  std::uint64_t holefill = 1;   // the hole-filling document
  std::uint64_t view = 1;       // what is drawn and how (points, normals, bounds box, slice, size, ...)
  std::uint64_t camera = 1;     // 3D camera, 2D centre and half height

  // Changes exactly when one of the concerns a fit reads changed (each counter only grows).
  std::uint64_t fitInputs() const { return data + fit + transform + patch + holefill; }
  bool operator==(const ConcernVersions&) const = default;
};

// Bumps the counter of every concern in which `after` differs from `before` (the view's camera
// keys count as the camera, the rest of `view` as the view).
void bumpChangedConcerns(ConcernVersions& versions, const Scene& before, const Scene& after);
// Bumps every counter (a new document).
void bumpAllConcerns(ConcernVersions& versions);

}  // namespace hermite::app
