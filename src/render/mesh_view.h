#pragma once
// Rasterised triangle meshes with lines on top (the patch editor's surface and iso-parameter
// lines, meshed implicits, hole filling stages): lit like the tracer (core/trace/shading.h), depth
// tested, drawn into an own offscreen target of the camera's size and read back, like the
// tracer's render(), so the application composes both the same way.

#include <vector>

#include <glm/fwd.hpp>

#include "core/trace/camera.h"
#include "core/trace/image.h"
#include "render/gl/gl_objects.h"

namespace hermite::render {

struct MeshDrawData {
  Points<3> positions;                            // 3 × V
  Points<3> normals;                              // 3 × V (unit; orientation decides front/back)
  Points<3> colors;                               // 3 × V base colours in [0, 1]; empty: the front colour
  Eigen::Matrix<int, 3, Eigen::Dynamic> triangles;  // 3 × T vertex indices
  // Lines as pairs of points with one colour per pair.
  std::vector<Vec<3>> lineEnds;                   // 2·L points
  std::vector<Vec<3>> lineColors;                 // L colours
  std::array<double, 3> background{1, 1, 1};
  double lineBias = 0.002;                        // lines pulled towards the eye by this × the mesh diagonal
};

class MeshView {
 public:
  // Needs a current GL 4.5 context; compiles mesh.vert/mesh.frag and the overlay line program.
  MeshView();
  // Draws the mesh and its lines and reads the image back (row 0 = top).
  ImageRgba8 render(const Camera& camera, const MeshDrawData& data);

 private:
  // The triangles, shaded with two lights and the back colour, depth-tested.
  void drawSurface(const Camera& camera, const glm::mat4& viewProj, const MeshDrawData& data);

  Program surface_, lines_;
  VertexArray surfaceVao_, linesVao_;
  Buffer vertices_, indices_, lineVertices_;
};

}  // namespace hermite::render
