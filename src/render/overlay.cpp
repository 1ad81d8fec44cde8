#include "render/overlay.h"

#include <cstddef>
#include <vector>

#include "render/gl/glm_convert.h"
#include "render/ground_grid.h"
#include "render/gl/shader_library.h"

namespace hermite::render {

namespace {

struct OverlayVertex {
  float position[3];
  float color[4];
};

void push(std::vector<OverlayVertex>& out, const Vec<3>& x, const glm::vec4& c) {
  out.push_back({{float(x.x()), float(x.y()), float(x.z())}, {c.r, c.g, c.b, c.a}});
}

// The line segments, two vertices each: the normals, the bounds' twelve edges, the ground grid.
void pushLines(std::vector<OverlayVertex>& vertices, const OverlayContent& content) {
  if (content.samples && content.showNormals) {
    const double length = content.normalLength * content.bounds.extent().norm();
    for (int s = 0; s < content.samples->size(); ++s) {
      const Vec<3> p = content.samples->points.col(s);
      push(vertices, p, content.normalColor);
      push(vertices, Vec<3>(p + length * content.samples->normals.col(s).normalized()), content.normalColor);
    }
  }
  if (content.showBounds) {
    const Box<3>& b = content.bounds;
    auto corner = [&](int c) {
      return Vec<3>((c & 1) ? b.hi.x() : b.lo.x(), (c & 2) ? b.hi.y() : b.lo.y(), (c & 4) ? b.hi.z() : b.lo.z());
    };
    for (int c = 0; c < 8; ++c)
      for (int bit = 1; bit <= 4; bit <<= 1)
        if (!(c & bit)) {
          push(vertices, corner(c), content.boundsColor);
          push(vertices, corner(c | bit), content.boundsColor);
        }
  }
  if (content.showGround) {
    const GroundGrid grid = groundGrid(content.samples ? content.samples->points : Points<3>(3, 0), content.bounds,
                                       content.groundUp);
    for (const auto& [a, b] : grid.segments) {
      push(vertices, a, content.groundColor);
      push(vertices, b, content.groundColor);
    }
  }
}

}  // namespace

OverlayRenderer::OverlayRenderer() : program_(buildProgram({"overlay.vert", "overlay.frag"})) {
  vertexArray_.setAttribute(0, 0, 3, GL_FLOAT, false, offsetof(OverlayVertex, position));
  vertexArray_.setAttribute(1, 0, 4, GL_FLOAT, false, offsetof(OverlayVertex, color));
}

void OverlayRenderer::draw(const Camera& camera, const glm::mat4& viewProj, const OverlayContent& content) {
  const double diagonal = content.bounds.extent().norm();
  // Lines first (normals, box, ground), then points, in one buffer.
  std::vector<OverlayVertex> vertices;
  pushLines(vertices, content);
  const int lineVertices = int(vertices.size());
  if (content.samples && content.showPoints)
    for (int s = 0; s < content.samples->size(); ++s) push(vertices, content.samples->points.col(s), content.pointColor);
  const int pointVertices = int(vertices.size()) - lineVertices;
  if (vertices.empty()) return;

  vertices_.setData(vertices.data(), vertices.size() * sizeof(OverlayVertex));
  vertexArray_.setVertexBuffer(0, vertices_, 0, sizeof(OverlayVertex));
  program_.use();
  program_.setUniform("uViewProj", viewProj);
  program_.setUniform("uEye", toGlm(camera.eye()));
  program_.setUniform("uForward", toGlm(camera.forward()));
  program_.setUniform("uOrtho", camera.projection() == Projection::Orthographic ? 1 : 0);
  // Samples lie on the surface: pull them 0.5 % of the diagonal towards the eye so they win
  // the depth test against their own surface but not against surface in front of them.
  program_.setUniform("uBias", float(0.005 * diagonal));
  program_.setUniform("uPointSize", content.pointSize);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_FALSE);
  glDisable(GL_BLEND);
  glEnable(GL_PROGRAM_POINT_SIZE);
  vertexArray_.bind();
  if (lineVertices > 0) {
    program_.setUniform("uRoundPoints", 0);
    glDrawArrays(GL_LINES, 0, lineVertices);
  }
  if (pointVertices > 0) {
    program_.setUniform("uRoundPoints", 1);
    glDrawArrays(GL_POINTS, lineVertices, pointVertices);
  }
  glDepthMask(GL_TRUE);
  checkGl("overlay draw");
}

}  // namespace hermite::render
