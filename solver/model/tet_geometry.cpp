#include "model/tet_geometry.hpp"

namespace needlefem {

namespace {
// Vertex pairs of the TET10 edge nodes 4..9 in gmsh order.
constexpr int kEdge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};

std::array<double, 4> barycentric(const std::array<double, 3>& xi) {
  return {1 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]};
}
// dL_i/dxi_j
constexpr double kDL[4][3] = {{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
}  // namespace

const std::vector<QuadraturePoint>& tet_quadrature_degree5() {
  static const std::vector<QuadraturePoint> rule = [] {
    std::vector<QuadraturePoint> points;
    auto add_corner_orbit = [&](double a, double w) {  // permutations of (a, a, a, 1 - 3a)
      const double b = 1 - 3 * a;
      points.push_back({{a, a, a}, w});
      points.push_back({{b, a, a}, w});
      points.push_back({{a, b, a}, w});
      points.push_back({{a, a, b}, w});
    };
    add_corner_orbit(0.0927352503108912, 0.01224884051939366);
    add_corner_orbit(0.3108859192633006, 0.01878132095300264);
    const double c = 0.4544962958743504, d = 0.5 - c, w = 0.007091003462846911;
    // permutations of (c, c, d, d) over the four barycentric coordinates, expressed in (L1, L2, L3)
    const std::array<std::array<double, 3>, 6> edge_orbit{{{c, c, d}, {c, d, c}, {d, c, c}, {c, d, d}, {d, c, d}, {d, d, c}}};
    for (const auto& xi : edge_orbit) points.push_back({xi, w});
    return points;
  }();
  return rule;
}

std::vector<std::array<double, 3>> tet_reference_nodes(int nodes_per_tet) {
  std::vector<std::array<double, 3>> nodes{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  if (nodes_per_tet == 10)
    for (const auto& e : kEdge)
      nodes.push_back({(nodes[e[0]][0] + nodes[e[1]][0]) / 2, (nodes[e[0]][1] + nodes[e[1]][1]) / 2,
                       (nodes[e[0]][2] + nodes[e[1]][2]) / 2});
  return nodes;
}

void tet_shape_values(int nodes_per_tet, const std::array<double, 3>& xi, double* N) {
  const auto L = barycentric(xi);
  if (nodes_per_tet == 4) {
    for (int i = 0; i < 4; ++i) N[i] = L[i];
    return;
  }
  for (int i = 0; i < 4; ++i) N[i] = L[i] * (2 * L[i] - 1);
  for (int k = 0; k < 6; ++k) N[4 + k] = 4 * L[kEdge[k][0]] * L[kEdge[k][1]];
}

void tet_shape_gradients(int nodes_per_tet, const std::array<double, 3>& xi, double* dN) {
  const auto L = barycentric(xi);
  if (nodes_per_tet == 4) {
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 3; ++j) dN[3 * i + j] = kDL[i][j];
    return;
  }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) dN[3 * i + j] = (4 * L[i] - 1) * kDL[i][j];
  for (int k = 0; k < 6; ++k) {
    const int a = kEdge[k][0], b = kEdge[k][1];
    for (int j = 0; j < 3; ++j) dN[3 * (4 + k) + j] = 4 * (kDL[a][j] * L[b] + L[a] * kDL[b][j]);
  }
}

double tet_jacobian_determinant(const TetMesh& mesh, std::size_t e, const std::array<double, 3>& xi) {
  double dN[30];
  tet_shape_gradients(mesh.nodes_per_tet, xi, dN);
  double J[3][3] = {};
  const int* t = mesh.tet(e);
  for (int i = 0; i < mesh.nodes_per_tet; ++i)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) J[r][c] += mesh.nodes[t[i]][r] * dN[3 * i + c];
  return J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
         J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
}

double tet_volume(const TetMesh& mesh, std::size_t e) {
  double volume = 0;
  for (const auto& q : tet_quadrature_degree5()) volume += q.weight * tet_jacobian_determinant(mesh, e, q.xi);
  return volume;
}

double oriented_volume(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])) /
         6;
}

}  // namespace needlefem
