#include "core/mesh/open_slivers.h"

#include <algorithm>
#include <vector>

namespace hermite {

int dropOpenSlivers(TriMesh& mesh, double maxArea) {
  int count = 0;
  std::vector<char> open;
  const std::vector<int> label = triangleComponents(mesh, &count, &open);
  if (count <= 1) return 0;  // the whole contour is never dropped
  std::vector<double> area(static_cast<size_t>(count), 0.0);
  for (int t = 0; t < mesh.triangleCount(); ++t)
    area[static_cast<size_t>(label[static_cast<size_t>(t)])] += triangleArea(mesh, t);
  std::vector<char> drop(static_cast<size_t>(count), 0);
  for (int c = 0; c < count; ++c)
    drop[static_cast<size_t>(c)] = open[static_cast<size_t>(c)] && area[static_cast<size_t>(c)] < maxArea;
  return dropComponents(mesh, label, drop);
}

int dropGridSlivers(TriMesh& mesh, const ImplicitField<3>& field, const Vec<3>& h) {
  if (field.everywhereValid() || vertexConnectedComponentCount(mesh) <= 1) return 0;
  return dropOpenSlivers(mesh, std::min({h[0] * h[1], h[1] * h[2], h[0] * h[2]}));
}

}  // namespace hermite
