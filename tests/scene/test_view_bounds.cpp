#include <doctest/doctest.h>

#include "core/base/errors.h"
#include "scene/view_bounds.h"

using namespace hermite;

TEST_CASE("view bounds: default is the samples' box grown by 25 % of its largest extent") {
  Points<3> P(3, 3);
  P << 0, 2, 1,  //
      0, 1, 0.5,  //
      -1, 0, 0;
  const Box<3> b = defaultViewBounds<3>(P);
  CHECK((b.lo - Vec<3>(-0.5, -0.5, -1.5)).norm() < 1e-15);
  CHECK((b.hi - Vec<3>(2.5, 1.5, 0.5)).norm() < 1e-15);
  // Coplanar points (z extent 0) still give a box with volume.
  P.row(2).setZero();
  const Box<3> flat = defaultViewBounds<3>(P);
  CHECK(flat.extent().z() == doctest::Approx(1.0));
  // One point: margin 1.
  const Box<2> single = defaultViewBounds<2>(Points<2>(Vec<2>(3, 4)));
  CHECK((single.lo - Vec<2>(2, 3)).norm() == 0.0);
  CHECK((single.hi - Vec<2>(4, 5)).norm() == 0.0);
  CHECK_THROWS_AS(defaultViewBounds<3>(Points<3>(3, 0)), InputError);
}

TEST_CASE("view bounds: view.bounds wins and is validated") {
  ViewSpec v;
  Points<3> P = Points<3>::Zero(3, 1);
  v.bounds = std::vector<double>{-1, -2, -3, 1, 2, 3};
  const Box<3> b = viewBounds<3>(v, P);
  CHECK((b.lo - Vec<3>(-1, -2, -3)).norm() == 0.0);
  CHECK((b.hi - Vec<3>(1, 2, 3)).norm() == 0.0);
  CHECK_THROWS_AS(viewBounds<2>(v, Points<2>::Zero(2, 1)), InputError);
  v.bounds = std::vector<double>{-1, -2, 3, 1, 2, 3};
  CHECK_THROWS_AS(viewBounds<3>(v, P), InputError);
  v.bounds.reset();
  CHECK(viewBounds<3>(v, P).extent().x() == doctest::Approx(2.0));
}
