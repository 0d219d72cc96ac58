// Geometry of straight and curved tetrahedra: Lagrange shape functions of TET4/TET10 in
// barycentric form, the Jacobian determinant of the map from the reference tetrahedron
// {xi, eta, zeta >= 0, xi + eta + zeta <= 1}, and a 14-point degree-5 quadrature
// (Walkington; positive weights summing to 1/6) that integrates the cubic det J of a TET10
// exactly, so element volumes are exact for curved elements.
//   TET4:  N_i = L_i.
//   TET10: N_i = L_i (2 L_i - 1) at vertices; N = 4 L_a L_b at the node of edge (a, b),
//          gmsh edge order (0,1) (1,2) (2,0) (3,0) (3,2) (3,1).
#pragma once

#include <array>
#include <vector>

#include "model/tet_mesh.hpp"

namespace needlefem {

struct QuadraturePoint {
  std::array<double, 3> xi;  // reference coordinates
  double weight;             // reference weight (sum 1/6)
};

const std::vector<QuadraturePoint>& tet_quadrature_degree5();
// Reference coordinates of the element's own nodes (4 or 10), in gmsh order.
std::vector<std::array<double, 3>> tet_reference_nodes(int nodes_per_tet);

// Shape-function derivatives dN_i/dxi_j at reference point xi: nodes_per_tet x 3, row-major.
void tet_shape_gradients(int nodes_per_tet, const std::array<double, 3>& xi, double* dN);
void tet_shape_values(int nodes_per_tet, const std::array<double, 3>& xi, double* N);

// det(dx/dxi) of element e at reference point xi.
double tet_jacobian_determinant(const TetMesh& mesh, std::size_t e, const std::array<double, 3>& xi);
double tet_volume(const TetMesh& mesh, std::size_t e);
// ((b - a) x (c - a)) . (d - a) / 6
double oriented_volume(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

}  // namespace needlefem
