// Progressive refined rows (issue 18, item 2): the GL thread copies each published row once, in
// order, and only of the newest refinement; rows a superseded job publishes later are dropped.

#include <doctest/doctest.h>

#include "app/gui/refined_rows.h"

using namespace hermite::app;

TEST_CASE("refined rows: each published row is taken once, in order") {
  RefinedRows rows;
  CHECK(rows.take(1, 16, 100).empty());  // nothing started
  rows.start(1);
  CHECK(rows.take(1, 0, 100).empty());
  CHECK(rows.take(1, 16, 100) == RowRange{0, 16});
  CHECK(rows.take(1, 16, 100).empty());  // nothing new
  CHECK(rows.take(1, 48, 100) == RowRange{16, 48});
  CHECK_FALSE(rows.complete(1, 100));
  CHECK(rows.take(1, 100, 100) == RowRange{48, 100});
  CHECK(rows.complete(1, 100));
  CHECK(rows.take(1, 100, 100).empty());
}

TEST_CASE("refined rows: the newest refinement wins and a superseded job's rows are dropped") {
  RefinedRows rows;
  rows.start(1);
  CHECK(rows.take(1, 32, 90) == RowRange{0, 32});
  rows.start(2);  // the camera moved: a refinement of the new view starts
  CHECK(rows.take(1, 64, 90).empty());  // the old job finishes bands after that: dropped
  CHECK_FALSE(rows.complete(1, 90));
  CHECK(rows.take(2, 16, 90) == RowRange{0, 16});  // the new one starts from the top
  rows.start(1);  // a late start of an older job changes nothing
  CHECK(rows.current() == 2);
  CHECK(rows.take(2, 90, 90) == RowRange{16, 90});
  CHECK(rows.complete(2, 90));
}

TEST_CASE("refined rows: a cleared view takes nothing, and rows never pass the image") {
  RefinedRows rows;
  rows.start(3);
  rows.clear();  // the view moved on without a new refinement (a gesture)
  CHECK_FALSE(rows.active());
  CHECK(rows.take(3, 50, 90).empty());
  rows.start(4);
  CHECK(rows.take(4, 500, 90) == RowRange{0, 90});  // clamped to the image's height
  CHECK(rows.take(4, 10, 90).empty());  // a smaller count than shown (never published) adds nothing
}
