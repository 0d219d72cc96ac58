// Block (cuboid) permanent magnet: flux density on its pole axis and the pull on a magnetic
// body in its field, after Tang, Chen & He, "Compliant needle modeling and steerable insertion
// simulation" (paper 000 in /work/shared/seeds), Section 2.2.
//
// Flux density at distance x in front of a pole face W x L of a magnet of thickness T
// magnetised along its thickness with residual flux density Br (Eq. 2.3):
//
//   B(x) = c Br/pi [ atan( L W / (2x sqrt(L^2 + W^2 + 4x^2)) )
//                  - atan( L W / (2(x+T) sqrt(L^2 + W^2 + 4(x+T)^2)) ) ]
//
// Each arctangent is a quarter of the solid angle the W x L rectangle subtends from the point
// (equivalent magnetic-charge model: B = Br/(4 pi) (Omega_near - Omega_far)). The paper calls
// Eq. 2.3 empirical and multiplies it by a correction factor c = 0.8-0.9 for real magnets.
// B(x) decreases monotonically from B(0) = c Br/pi [pi/2 - atan(LW/(2T sqrt(L^2+W^2+4T^2)))]
// to zero, so every B in (0, B(0)) is reached at exactly one distance.
//
// Force on the pole area A_g = W L through the gap (Eq. 2.1-2.2):
//   F = B_g H_g A_g / 2,  B = mu0 (1 + chi_m) H   =>   F = B^2 A_g / (2 mu0 (1 + chi_m)),
// which in air (chi_m = 0) is the paper's F = B^2 A_g / (8 pi 1e-7) with B in T, A_g in m^2.
#pragma once

#include <numbers>

namespace needlefem::steering {

// Vacuum permeability as the paper uses it (8 pi 1e-7 = 2 mu0), in H/m.
inline constexpr double vacuum_permeability_h_per_m = 4.0e-7 * std::numbers::pi;

struct BlockMagnet {
  double residual_flux_density_t = 0.0;  // Br
  double pole_width_m = 0.0;             // W
  double pole_length_m = 0.0;            // L
  double thickness_m = 0.0;              // T, along the magnetisation
  double correction_factor = 1.0;        // c, paper: 0.8-0.9

  double pole_area_m2() const { return pole_width_m * pole_length_m; }
  // Throws std::invalid_argument naming the first non-positive dimension.
  void validate() const;
};

// Eq. 2.3 times the correction factor; distance_m >= 0 from the pole face along its axis.
double axial_flux_density_t(const BlockMagnet& magnet, double distance_m);

// The distance at which axial_flux_density_t equals flux_density_t (root of Eq. 2.3, found by
// bisection on the monotonic B(x)). Throws std::domain_error when the wanted flux density is
// not positive or exceeds what the magnet gives at its face.
double distance_for_flux_density_m(const BlockMagnet& magnet, double flux_density_t);

// Eq. 2.1-2.2: pull on the gap area A_g for gap flux density B in a medium of susceptibility chi_m.
double gap_force_n(double flux_density_t, double gap_area_m2, double susceptibility = 0.0);

}  // namespace needlefem::steering
