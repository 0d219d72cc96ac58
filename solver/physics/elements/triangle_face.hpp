// Boundary faces of the tetrahedra (TRI3, TRI6; node order of model/tet_mesh.hpp): shape
// functions and the quadrature rule that surface terms (contact, pressure) integrate with.
#pragma once

#include <array>

namespace needlefem::elements {

// Dunavant (1985) 6-point, degree-4 rule on the reference triangle (area 1/2): (L1, L2, weight).
struct TrianglePoint {
  double xi, eta, weight;
};
inline constexpr double kDunavantA = 0.445948490915965, kDunavantB = 0.091576213509771;
inline constexpr double kDunavantWa = 0.5 * 0.223381589678011, kDunavantWb = 0.5 * 0.109951743655322;
inline constexpr std::array<TrianglePoint, 6> kTriangleRule{{{kDunavantA, kDunavantA, kDunavantWa},
                                                             {1.0 - 2.0 * kDunavantA, kDunavantA, kDunavantWa},
                                                             {kDunavantA, 1.0 - 2.0 * kDunavantA, kDunavantWa},
                                                             {kDunavantB, kDunavantB, kDunavantWb},
                                                             {1.0 - 2.0 * kDunavantB, kDunavantB, kDunavantWb},
                                                             {kDunavantB, 1.0 - 2.0 * kDunavantB, kDunavantWb}}};

// TRI3 / TRI6 shape functions and their (ξ, η) derivatives; L0 = 1 - ξ - η, L1 = ξ, L2 = η;
// TRI6 edge nodes (0,1) (1,2) (2,0).
inline void triangle_shape(int nodes, double xi, double eta, double* N, double* dN_dxi, double* dN_deta) {
  const double l0 = 1.0 - xi - eta, l1 = xi, l2 = eta;
  if (nodes == 3) {
    N[0] = l0, N[1] = l1, N[2] = l2;
    dN_dxi[0] = -1.0, dN_dxi[1] = 1.0, dN_dxi[2] = 0.0;
    dN_deta[0] = -1.0, dN_deta[1] = 0.0, dN_deta[2] = 1.0;
    return;
  }
  N[0] = l0 * (2.0 * l0 - 1.0), N[1] = l1 * (2.0 * l1 - 1.0), N[2] = l2 * (2.0 * l2 - 1.0);
  N[3] = 4.0 * l0 * l1, N[4] = 4.0 * l1 * l2, N[5] = 4.0 * l2 * l0;
  // dL0 = (-1, -1), dL1 = (1, 0), dL2 = (0, 1).
  dN_dxi[0] = -(4.0 * l0 - 1.0), dN_dxi[1] = 4.0 * l1 - 1.0, dN_dxi[2] = 0.0;
  dN_dxi[3] = 4.0 * (l0 - l1), dN_dxi[4] = 4.0 * l2, dN_dxi[5] = -4.0 * l2;
  dN_deta[0] = -(4.0 * l0 - 1.0), dN_deta[1] = 0.0, dN_deta[2] = 4.0 * l2 - 1.0;
  dN_deta[3] = -4.0 * l1, dN_deta[4] = 4.0 * l1, dN_deta[5] = 4.0 * (l0 - l2);
}

}  // namespace needlefem::elements
