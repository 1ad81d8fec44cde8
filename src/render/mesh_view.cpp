#include "render/mesh_view.h"
#include "render/gl/glm_convert.h"

#include <glm/glm.hpp>

#include <cstddef>

#include "core/trace/shading.h"
#include "render/gl/offscreen.h"
#include "render/gl/shader_library.h"

namespace hermite::render {

namespace {

struct SurfaceVertex {
  float position[3];
  float normal[3];
  float color[3];
};

struct LineVertex {
  float position[3];
  float color[4];
};

// The box of the vertices and the line ends.
Box<3> drawnBox(const MeshDrawData& data) {
  Box<3> box;
  if (data.positions.cols() > 0) box = boundingBox<3>(data.positions);
  for (const Vec<3>& p : data.lineEnds) {
    box.lo = box.lo.cwiseMin(p);
    box.hi = box.hi.cwiseMax(p);
  }
  return box;
}

// Interleaved float vertices; the front colour where the data have no per-vertex colours.
std::vector<SurfaceVertex> surfaceVertices(const MeshDrawData& data) {
  const int V = int(data.positions.cols());
  std::vector<SurfaceVertex> vertices(V);
  for (int i = 0; i < V; ++i) {
    const Vec<3> c = data.colors.cols() == V
                         ? Vec<3>(data.colors.col(i))
                         : Vec<3>(shading::kFrontColor[0], shading::kFrontColor[1], shading::kFrontColor[2]);
    for (int k = 0; k < 3; ++k) {
      vertices[i].position[k] = float(data.positions(k, i));
      vertices[i].normal[k] = float(data.normals(k, i));
      vertices[i].color[k] = float(c(k));
    }
  }
  return vertices;
}

// Two vertices per segment, opaque, in the segment's colour.
std::vector<LineVertex> lineVertices(const MeshDrawData& data) {
  std::vector<LineVertex> lines(data.lineEnds.size());
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const Vec<3>& c = data.lineColors[k / 2];
    for (int a = 0; a < 3; ++a) {
      lines[k].position[a] = float(data.lineEnds[k](a));
      lines[k].color[a] = float(c(a));
    }
    lines[k].color[3] = 1.0f;
  }
  return lines;
}

// The uniforms both programs share: the camera's transform, eye, direction and projection kind.
void setCameraUniforms(Program& program, const Camera& camera, const glm::mat4& viewProj) {
  program.use();
  program.setUniform("uViewProj", viewProj);
  program.setUniform("uEye", toGlm(camera.eye()));
  program.setUniform("uForward", toGlm(camera.forward()));
  program.setUniform("uOrtho", camera.projection() == Projection::Orthographic ? 1 : 0);
}

}  // namespace

MeshView::MeshView()
    : surface_(buildProgram({"mesh.vert", "mesh.frag"})), lines_(buildProgram({"overlay.vert", "overlay.frag"})) {
  surfaceVao_.setAttribute(0, 0, 3, GL_FLOAT, false, offsetof(SurfaceVertex, position));
  surfaceVao_.setAttribute(1, 0, 3, GL_FLOAT, false, offsetof(SurfaceVertex, normal));
  surfaceVao_.setAttribute(2, 0, 3, GL_FLOAT, false, offsetof(SurfaceVertex, color));
  linesVao_.setAttribute(0, 0, 3, GL_FLOAT, false, offsetof(LineVertex, position));
  linesVao_.setAttribute(1, 0, 4, GL_FLOAT, false, offsetof(LineVertex, color));
}

ImageRgba8 MeshView::render(const Camera& camera, const MeshDrawData& data) {
  const Box<3> box = drawnBox(data);
  const double diagonal = std::max(box.extent().norm(), 1e-9);
  Box<3> padded = box;
  padded.lo.array() -= 0.05 * diagonal;
  padded.hi.array() += 0.05 * diagonal;
  const Eigen::Vector2d range = camera.depthRange(padded);
  const glm::mat4 viewProj = toGlm(Eigen::Matrix4d(camera.projectionMatrix(range(0), range(1)) * camera.viewMatrix()));

  OffscreenTarget target(camera.width(), camera.height(), true);
  target.bind();
  glClearColor(float(data.background[0]), float(data.background[1]), float(data.background[2]), 1.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  if (data.positions.cols() > 0 && data.triangles.cols() > 0) drawSurface(camera, viewProj, data);
  if (!data.lineEnds.empty()) {
    const std::vector<LineVertex> lines = lineVertices(data);
    lineVertices_.setData(lines.data(), lines.size() * sizeof(LineVertex));
    linesVao_.setVertexBuffer(0, lineVertices_, 0, sizeof(LineVertex));
    setCameraUniforms(lines_, camera, viewProj);
    lines_.setUniform("uBias", float(data.lineBias * diagonal));
    lines_.setUniform("uPointSize", 1.0f);
    lines_.setUniform("uRoundPoints", 0);
    glDepthMask(GL_FALSE);
    linesVao_.bind();
    glDrawArrays(GL_LINES, 0, GLsizei(lines.size()));
    glDepthMask(GL_TRUE);
  }
  glBindVertexArray(0);
  checkGl("mesh view");
  return target.read();
}

void MeshView::drawSurface(const Camera& camera, const glm::mat4& viewProj, const MeshDrawData& data) {
  const std::vector<SurfaceVertex> vertices = surfaceVertices(data);
  vertices_.setData(vertices.data(), vertices.size() * sizeof(SurfaceVertex));
  indices_.setData(data.triangles.data(), std::size_t(data.triangles.size()) * sizeof(int));
  surfaceVao_.setVertexBuffer(0, vertices_, 0, sizeof(SurfaceVertex));
  surfaceVao_.setElementBuffer(indices_);
  setCameraUniforms(surface_, camera, viewProj);
  for (int k = 0; k < 2; ++k) {
    const Vec<3> l = shading::lightDirection(shading::kLights[k], camera.right(), camera.up(), camera.forward());
    surface_.setUniform("uLightDir[" + std::to_string(k) + "]", toGlm(l));
    surface_.setUniform("uLightIntensity[" + std::to_string(k) + "]", float(shading::kLights[k].intensity));
  }
  surface_.setUniform("uAmbient", float(shading::kAmbient));
  surface_.setUniform("uBackColor", toGlm(shading::kBackColor));
  surfaceVao_.bind();
  glDrawElements(GL_TRIANGLES, GLsizei(data.triangles.size()), GL_UNSIGNED_INT, nullptr);
}

}  // namespace hermite::render
