#include "app/gui/concern_versions.h"

namespace hermite::app {

namespace {

bool sameCamera(const ViewSpec& a, const ViewSpec& b) {
  return a.camera == b.camera && a.center2d == b.center2d && a.halfHeight2d == b.halfHeight2d;
}

// The view without its camera keys.
bool sameViewButCamera(const ViewSpec& a, const ViewSpec& b) {
  ViewSpec withBCamera = a;
  withBCamera.camera = b.camera;
  withBCamera.center2d = b.center2d;
  withBCamera.halfHeight2d = b.halfHeight2d;
  return withBCamera == b;
}

}  // namespace

void bumpChangedConcerns(ConcernVersions& v, const Scene& before, const Scene& after) {
  // The mode and the source name (which prefixes a fit's messages) count as data.
  if (!(before.data == after.data) || before.mode != after.mode || before.sourceName != after.sourceName ||
      before.version != after.version)
    ++v.data;
  if (!(before.fit == after.fit)) ++v.fit;
  if (!(before.transform == after.transform)) ++v.transform;
  if (!(before.patch == after.patch)) ++v.patch;
  if (!(before.holefill == after.holefill)) ++v.holefill;
  if (!sameViewButCamera(before.view, after.view)) ++v.view;
  if (!sameCamera(before.view, after.view)) ++v.camera;
}

void bumpAllConcerns(ConcernVersions& v) {
  for (std::uint64_t* c : {&v.data, &v.fit, &v.transform, &v.patch, &v.holefill, &v.view, &v.camera}) ++*c;
}

}  // namespace hermite::app
