#pragma once
// The Stanford bunny point set (assets/bunny/bunny.xyzn, see assets/bunny/README.md), embedded
// into the library at build time so that no file is read at run time.

#include <string_view>

namespace hermite {

// The text of bunny.xyzn: one "x y z nx ny nz" line per vertex.
std::string_view embeddedBunnyXyzn();

}  // namespace hermite
