// The document's per-concern version counters: each edit bumps exactly the concerns it touches,
// so that a view or camera change never reads as a change of what a fit reads.

#include <doctest/doctest.h>

#include "app/gui/document.h"

using namespace hermite;
using namespace hermite::app;

namespace {

Scene sphereScene() {
  Scene s;
  s.mode = SceneMode::Implicit3d;
  s.data.preset = "sphere";
  s.data.count = 30;
  return s;
}

}  // namespace

TEST_CASE("concern versions: a view toggle and a camera move leave the fit inputs alone; a fit setting does not") {
  Document d(sphereScene());
  const ConcernVersions v0 = d.versions();
  Scene s = d.scene();
  s.view.showBounds = true;
  d.apply(s, "bounds box");
  ConcernVersions v1 = d.versions();
  CHECK(v1.view == v0.view + 1);
  CHECK(v1.camera == v0.camera);
  CHECK(v1.fitInputs() == v0.fitInputs());

  CameraSpec c = d.scene().view.camera;
  c.eye[0] += 0.5;
  d.setCamera(c, d.scene().view.center2d, d.scene().view.halfHeight2d);
  const ConcernVersions v2 = d.versions();
  CHECK(v2.camera == v1.camera + 1);
  CHECK(v2.view == v1.view);
  CHECK(v2.fitInputs() == v1.fitInputs());

  s = d.scene();
  s.fit.radius = 0.7;
  d.apply(s, "radius");
  const ConcernVersions v3 = d.versions();
  CHECK(v3.fit == v2.fit + 1);
  CHECK(v3.data == v2.data);
  CHECK(v3.view == v2.view);
  CHECK(v3.fitInputs() > v2.fitInputs());

  // Undo restores the radius (a fit change again) and keeps the camera where it is.
  d.undo();
  const ConcernVersions v4 = d.versions();
  CHECK(v4.fit == v3.fit + 1);
  CHECK(v4.camera == v3.camera);
  CHECK(d.scene().fit.radius == sphereScene().fit.radius);
}

TEST_CASE("concern versions: data, transform and mode edits bump their own counters; reset bumps all") {
  Document d(sphereScene());
  const ConcernVersions v0 = d.versions();
  Scene s = d.scene();
  s.data.count = 40;
  d.apply(s, "count");
  CHECK(d.versions().data == v0.data + 1);
  CHECK(d.versions().fit == v0.fit);
  s.transform.scale = 2.0;
  d.apply(s, "scale");
  CHECK(d.versions().transform == v0.transform + 1);
  CHECK(d.versions().data == v0.data + 1);
  s.mode = SceneMode::Patch;
  d.apply(s, "patch editor");
  CHECK(d.versions().data == v0.data + 2);  // the mode is part of what is fitted
  const ConcernVersions before = d.versions();
  d.reset(sphereScene(), "");
  const ConcernVersions& r = d.versions();
  CHECK(r.data > before.data);
  CHECK(r.fit > before.fit);
  CHECK(r.view > before.view);
  CHECK(r.camera > before.camera);
}
