#include "core/shapes/mesh_shapes.h"

#include <cmath>
#include <vector>

namespace hermite {

TriMesh parametricTorusMesh(int nu, int nv, double R, double r) {
  TriMesh m;
  m.vertices.resize(3, nu * nv);
  m.triangles.resize(3, 2 * nu * nv);
  const auto id = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
      m.vertices.col(id(i, j)) =
          Vec<3>((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
      m.triangles.col(2 * id(i, j)) = Eigen::Vector3i(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      m.triangles.col(2 * id(i, j) + 1) = Eigen::Vector3i(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  return m;
}

TriMesh uvSphereMesh(int nu, int nv) {
  TriMesh m;
  const int rings = nv - 1;  // latitude rings without the poles
  m.vertices.resize(3, nu * rings + 2);
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < nu; ++i) {
      const double th = M_PI * (j + 1) / nv, ph = 2 * M_PI * i / nu;
      m.vertices.col(j * nu + i) = Vec<3>(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
    }
  const int north = nu * rings, south = north + 1;
  m.vertices.col(north) = Vec<3>(0, 0, 1);
  m.vertices.col(south) = Vec<3>(0, 0, -1);
  std::vector<Eigen::Vector3i> t;
  for (int i = 0; i < nu; ++i) {
    const int a = i, b = (i + 1) % nu;
    t.emplace_back(north, a, b);
    for (int j = 0; j + 1 < rings; ++j) {
      const int p = j * nu + a, q = j * nu + b, p2 = p + nu, q2 = q + nu;
      t.emplace_back(p, p2, q2);
      t.emplace_back(p, q2, q);
    }
    t.emplace_back(south, (rings - 1) * nu + b, (rings - 1) * nu + a);
  }
  m.triangles.resize(3, Eigen::Index(t.size()));
  for (std::size_t k = 0; k < t.size(); ++k) m.triangles.col(Eigen::Index(k)) = t[k];
  return m;
}

TriMesh openWavySphereMesh(int nu, int nv, int openRings, double wave) {
  TriMesh m = uvSphereMesh(nu, nv);
  const int north = nu * (nv - 1), firstKept = openRings * nu;  // ring j holds ids j·nu … j·nu + nu − 1
  std::vector<int> keep;
  for (int t = 0; t < m.triangleCount(); ++t) {
    bool open = false;
    for (int k = 0; k < 3; ++k) open |= m.triangles(k, t) == north || m.triangles(k, t) < firstKept;
    if (!open) keep.push_back(t);
  }
  TriMesh out = m;
  out.triangles.resize(3, Eigen::Index(keep.size()));
  for (std::size_t k = 0; k < keep.size(); ++k) out.triangles.col(Eigen::Index(k)) = m.triangles.col(keep[k]);
  for (Eigen::Index v = 0; v < out.vertices.cols(); ++v) {
    const double x = out.vertices(0, v), y = out.vertices(1, v);
    out.vertices(2, v) += wave * (3 * x * x * y - y * y * y);
  }
  return out;
}

TriMesh holedTorusMesh(int nu, int nv, int around, int across, double minRadius, double maxRadius) {
  const double R = 0.7, r = 0.3;
  TriMesh holed = parametricTorusMesh(nu, nv, R, r);
  for (int a = 0; a < around; ++a)
    for (int b = 0; b < across; ++b) {
      const double u = 2 * M_PI * (a + 0.5 * (b % 2)) / around, v = 2 * M_PI * (b + 0.5) / across;
      const double radius = minRadius + (maxRadius - minRadius) * double((7 * a + 3 * b) % 10) / 9.0;
      holed = cutBall(holed, Vec<3>((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)),
                      radius);
    }
  return holed;
}

TriMesh cutBall(const TriMesh& mesh, const Vec<3>& centre, double radius) {
  std::vector<int> keep;
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    bool inside = false;
    for (int k = 0; k < 3; ++k) inside |= (mesh.vertices.col(mesh.triangles(k, t)) - centre).norm() < radius;
    if (!inside) keep.push_back(t);
  }
  TriMesh out = mesh;
  out.triangles.resize(3, Eigen::Index(keep.size()));
  for (std::size_t k = 0; k < keep.size(); ++k) out.triangles.col(Eigen::Index(k)) = mesh.triangles.col(keep[k]);
  return out;
}

}  // namespace hermite
