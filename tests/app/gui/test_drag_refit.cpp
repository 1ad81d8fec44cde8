// The GUI's drag refits (app/gui/drag_refit.h): which scenes take the bordered solve, and that its
// field is the field of the fit from scratch.
#include <doctest/doctest.h>

#include "app/gui/document.h"
#include "app/gui/drag_refit.h"

using namespace hermite;
using namespace hermite::app;

namespace {

template <int Dim>
Scene inlineScene(const char* preset, int count) {
  Scene s;
  s.mode = Dim == 2 ? SceneMode::Implicit2d : SceneMode::Implicit3d;
  s.data.preset = preset;
  s.data.count = count;
  std::vector<std::string> warnings;
  return withInlineSamples<Dim>(s, warnings);
}

template <int Dim>
Scene moved(Scene s, int sample, const Vec<Dim>& by, bool turnNormal = false) {
  HermiteSamples<Dim> d = inlineSamples<Dim>(s);
  d.points.col(sample) += by;
  if (turnNormal) d.normals.col(sample) = (d.normals.col(sample) + by / by.norm()).normalized();
  setInlineSamples<Dim>(s, d);
  return s;
}

template <int Dim>
const SceneFit<Dim>& sceneFit(const FitOutcome& o) {
  if constexpr (Dim == 2)
    return *o.as<SceneFit<2>>();
  else
    return *o.as<SceneFit<3>>();
}

// max |f_a − f_b| over the samples and a ring of probes around them, relative to max |∇f_b|·extent.
template <int Dim>
double fieldDifference(const FitOutcome& a, const FitOutcome& b) {
  const SceneFit<Dim>& fa = sceneFit<Dim>(a);
  const SceneFit<Dim>& fb = sceneFit<Dim>(b);
  Points<Dim> X(Dim, 2 * fb.data.size());
  X << fb.data.points + 0.1 * fb.data.normals, fb.data.points - 0.2 * fb.data.normals;
  Eigen::VectorXd va, vb;
  fa.field().evaluateBatch(X, va);
  fb.field().evaluateBatch(X, vb);
  return (va - vb).cwiseAbs().maxCoeff() / vb.cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("drag refit: moving or turning one sample takes the bordered solve and gives the fit from scratch") {
  DragRefit refit;
  Scene scene = inlineScene<2>("curve2d", 60);
  auto first = refit.fit(scene);
  REQUIRE(first->ok());
  CHECK(refit.borderedFits() == 0);
  CHECK(first->as<SceneFit<2>>()->report.solver != "bordered-lu");

  for (int step = 1; step <= 3; ++step) {
    scene = moved<2>(scene, 7, Vec<2>(0.02, -0.01), step == 3);
    auto fast = refit.fit(scene);
    REQUIRE(fast->ok());
    CHECK(fast->as<SceneFit<2>>()->report.solver == "bordered-lu");
    CHECK(fieldDifference<2>(*fast, *fitOutcome(scene)) < 1e-9);
  }
  CHECK(refit.borderedFits() == 3);
  CHECK(refit.factorisations() == 1);  // one per dragged sample, not per move

  // Another sample: a new factorisation, still bordered.
  scene = moved<2>(scene, 30, Vec<2>(-0.03, 0.01));
  CHECK(refit.fit(scene)->as<SceneFit<2>>()->report.solver == "bordered-lu");
  CHECK(refit.factorisations() == 2);

  // A changed setting, two samples at once, a partition of unity: from scratch.
  scene.fit.radius *= 2;
  CHECK(refit.fit(scene)->as<SceneFit<2>>()->report.solver != "bordered-lu");
  scene = moved<2>(moved<2>(scene, 3, Vec<2>(0.01, 0.0)), 4, Vec<2>(0.0, 0.01));
  CHECK(refit.fit(scene)->as<SceneFit<2>>()->report.solver != "bordered-lu");
  scene.fit.partition.enabled = PartitionSwitch::On;
  scene = moved<2>(scene, 5, Vec<2>(0.01, 0.0));
  auto pu = refit.fit(scene);
  REQUIRE(pu->ok());
  CHECK(pu->as<SceneFit<2>>()->pu() != nullptr);
  CHECK(refit.borderedFits() == 4);
}

TEST_CASE("drag refit: 3D, and bad data still gets the error of the fit from scratch") {
  DragRefit refit;
  Scene scene = inlineScene<3>("sphere", 80);
  REQUIRE(refit.fit(scene)->ok());
  scene = moved<3>(scene, 11, Vec<3>(0.03, -0.02, 0.05));
  auto fast = refit.fit(scene);
  REQUIRE(fast->ok());
  CHECK(fast->as<SceneFit<3>>()->report.solver == "bordered-lu");
  CHECK(fieldDifference<3>(*fast, *fitOutcome(scene)) < 1e-9);

  // A non-finite coordinate: not a drag refit, the validation's error.
  HermiteSamples<3> d = inlineSamples<3>(scene);
  d.points(0, 11) = std::numeric_limits<double>::quiet_NaN();
  setInlineSamples<3>(scene, d);
  auto bad = refit.fit(scene);
  CHECK_FALSE(bad->ok());
  CHECK(bad->error == fitOutcome(scene)->error);
}

TEST_CASE("drag refit: a prepared drag refits its very first move through the bordered solve") {
  DragRefit refit;
  Scene scene = inlineScene<2>("curve2d", 50);
  refit.prepare(scene, 12);  // as the GUI does when the sample is grabbed, before any fit here
  CHECK(refit.factorisations() == 1);
  refit.prepare(scene, 12);  // the same drag again: nothing to do
  CHECK(refit.factorisations() == 1);
  scene = moved<2>(scene, 12, Vec<2>(0.01, 0.02));
  auto first = refit.fit(scene);
  REQUIRE(first->ok());
  CHECK(first->as<SceneFit<2>>()->report.solver == "bordered-lu");
  CHECK(fieldDifference<2>(*first, *fitOutcome(scene)) < 1e-9);
  CHECK(refit.factorisations() == 1);
}

TEST_CASE("drag refit: an edited scan's bordered refit keeps its data reach, as the fit from scratch does") {
  DragRefit refit;
  Scene scene = inlineScene<2>("curve2d", 60);
  scene.fit.reachMask = AutoSwitch::On;  // what a file's samples made inline carry (withInlineSamples)
  REQUIRE(refit.fit(scene)->ok());
  scene = moved<2>(scene, 7, Vec<2>(0.02, -0.01));
  const auto fast = refit.fit(scene);
  REQUIRE(fast->ok());
  CHECK(fast->as<SceneFit<2>>()->report.solver == "bordered-lu");
  CHECK_FALSE(fast->as<SceneFit<2>>()->field().everywhereValid());
  const auto scratch = fitOutcome(scene);
  CHECK_FALSE(scratch->as<SceneFit<2>>()->field().everywhereValid());
  // The same validity: far from the curve neither has data, on a sample both have.
  const Vec<2> far(50.0, 50.0), on = fast->as<SceneFit<2>>()->data.points.col(0);
  CHECK_FALSE(fast->as<SceneFit<2>>()->field().valid(far));
  CHECK(fast->as<SceneFit<2>>()->field().valid(on));
  CHECK(scratch->as<SceneFit<2>>()->field().valid(on));
}
