// Pseudo-rigid-body model (PRBM) of paper 000's compliant needle (Tang, Chen & He, Section 2.2):
// a rigid magnetised head of length L joined to the fixed shaft by a short flexural pivot
// (the weakened neck, length l, diameter d), turned by the magnet's pull F acting at angle phi
// to the head, against the neck's bending stiffness and the tissue around the head.
//
//   neck torsion spring      K   = (E I)_l / l,  I = pi d^4 / 64                      (Eq. 2.6)
//   tissue moment            M_t = theta mu_t/3 (l/2 + L)^3                           (Eq. 2.4)
//     (a triangular load mu_t theta s along the lever s in [0, l/2 + L]; mu_t is the tissue's
//      spring constant per unit length, N/m^2)
//   moment balance           F cos(phi) (L + l)/2 - M_t = K theta                     (Eq. 2.5)
//   turning angle            theta = F cos(phi) (L + l)/2 / (K + mu_t/3 (l/2 + L)^3)   (Eq. 2.7)
//   flux density for theta   B = sqrt( 2 mu0 * 2 theta (K + mu_t/3 (l/2 + L)^3)
//                                      / (cos(phi) (L + l) A_g) )                      (Eq. 2.8)
// with F = B^2 A_g / (2 mu0) (Eq. 2.1-2.2 in air).
//
// Eq. 2.8 as printed omits the gap area A_g; it follows from Eq. 2.7 only with A_g under the
// root. With A_g = 0.05 m x 0.06 m, steel E = 200 GPa, phi = 0, mu_t = 0, l = 1 mm, L = 3.5 mm,
// d = 0.2 mm it gives 15 deg -> 0.039130 T and 30 deg -> 0.055338 T, the paper's printed
// 0.0391 T and 0.0553 T (tests/steering/test_hinge.cpp checks this).
#pragma once

namespace needlefem::steering {

struct CompliantNeedleHinge {
  double neck_length_m = 0.0;      // l
  double neck_diameter_m = 0.0;    // d
  double head_length_m = 0.0;      // L
  double youngs_modulus_pa = 0.0;  // E of the neck material
  double tissue_spring_constant_n_per_m2 = 0.0;  // mu_t; 0 = turning in air

  // Throws std::invalid_argument naming the first invalid parameter.
  void validate() const;
  double neck_second_moment_m4() const;          // I = pi d^4 / 64
  double hinge_stiffness_n_m_per_rad() const;    // K = E I / l
  double tissue_stiffness_n_m_per_rad() const;   // mu_t/3 (l/2 + L)^3
  double lever_arm_m() const;                    // (L + l)/2, from the pivot to the head's centre
};

// Eq. 2.7: head turning angle (rad) under a pull force_n at force_angle_rad (phi) to the head.
double turning_angle_rad(const CompliantNeedleHinge& hinge, double force_n, double force_angle_rad);

// Eq. 2.7 with the force of Eq. 2.1-2.2 in air for gap flux density B on gap area A_g.
double turning_angle_for_flux_density_rad(const CompliantNeedleHinge& hinge, double flux_density_t,
                                          double gap_area_m2, double force_angle_rad);

// Eq. 2.8 (with A_g): the gap flux density that turns the head by turning_angle_rad.
// Throws std::domain_error when the angle is negative or cos(phi) <= 0 (the pull cannot turn the head).
double flux_density_for_turning_angle_t(const CompliantNeedleHinge& hinge, double turning_angle_rad,
                                        double gap_area_m2, double force_angle_rad);

}  // namespace needlefem::steering
