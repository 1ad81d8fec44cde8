#pragma once
// Overlays of the 3D view: samples as points, their normals as short lines and the bounds box,
// drawn into the bound framebuffer with the depth test on (against the depth the implicit
// tracer wrote), so the surface hides what lies behind it.

#include <glm/glm.hpp>

#include "core/points/hermite_samples.h"
#include "core/trace/camera.h"
#include "render/gl/gl_objects.h"

namespace hermite::render {

struct OverlayContent {
  const HermiteSamples<3>* samples = nullptr;  // may be null: no points, no normals
  bool showPoints = true;
  bool showNormals = true;
  bool showBounds = false;
  bool showGround = false;       // the ground grid (ground_grid.h) under the samples (the bounds without)
  Vec<3> groundUp = Vec<3>(0, 1, 0);  // the grid's plane is across this direction
  Box<3> bounds;                 // the view bounds: box lines, and the scale of normals and bias
  float pointSize = 4.0f;        // pixels
  double normalLength = 0.05;    // fraction of the bounds diagonal
  glm::vec4 pointColor{0.10f, 0.10f, 0.10f, 1.0f};
  glm::vec4 normalColor{0.05f, 0.45f, 0.15f, 1.0f};
  glm::vec4 boundsColor{0.35f, 0.35f, 0.35f, 1.0f};
  glm::vec4 groundColor{0.62f, 0.62f, 0.62f, 1.0f};
};

class OverlayRenderer {
 public:
  // Needs a current GL 4.5 context; compiles overlay.vert/overlay.frag.
  OverlayRenderer();

  // Draws with the current framebuffer and viewport; viewProj = P·V of the camera (the matrix
  // the tracer used for gl_FragDepth). Leaves the depth test on, depth writes off, blending off.
  void draw(const Camera& camera, const glm::mat4& viewProj, const OverlayContent& content);

 private:
  Program program_;
  VertexArray vertexArray_;
  Buffer vertices_;
};

}  // namespace hermite::render
