// PRBM check (issue 6, item 3): the pseudo-rigid-body turning angle of paper 000's compliant
// needle (Eq. 2.7, steering/hinge.hpp: theta = F (L + l)/2 / K, K = E I / l, phi = 0, in air:
// mu_t = 0) against the large-rotation 3-D FEM of the tip (prbm_check/tip_statics.hpp) under the
// same head load, over a range of loads. The loads are chosen as those for which the PRBM gives
// the angles prbm_check.angles_deg; each is solved as a follower load (paper 000's assumption) and
// as a dead load (fixed direction), and the small-displacement FEM angle is reported alongside,
// so the table separates the PRBM's hinge idealisation (PRBM vs linear FEM: neck-root compliance,
// 3-D stress state) from geometric nonlinearity (nonlinear vs linear FEM).
#pragma once

#include <string>
#include <vector>

#include "case/case.hpp"

namespace needlefem::prbm {

struct PrbmCheckRow {
  double force_n = 0.0;
  double prbm_deg = 0.0;             // Eq. 2.7 with the paper's lever (L + l)/2
  double prbm_load_lever_deg = 0.0;  // Eq. 2.7 with the FEM load's lever (differs with a conical point)
  double fem_follower_deg = 0.0;
  double fem_dead_deg = 0.0;
  double fem_linear_deg = 0.0;
  int follower_newton = 0, dead_newton = 0;  // Newton iterations to reach this load from the previous
  double max_corotated_strain = 0.0;         // at the follower solution
  double error_percent() const { return 100.0 * (prbm_deg - fem_follower_deg) / fem_follower_deg; }
  double dead_error_percent() const { return 100.0 * (prbm_deg - fem_dead_deg) / fem_dead_deg; }
};

struct PrbmCheckResult {
  std::vector<PrbmCheckRow> rows;
  double youngs_modulus_pa = 0.0, poisson_ratio = 0.0;
  double hinge_stiffness_n_m_per_rad = 0.0;  // K = E I / l
  double fem_stiffness_n_m_per_rad = 0.0;    // F a / theta of the small-displacement FEM
  double prbm_lever_m = 0.0, fem_load_lever_m = 0.0;
  double tolerance_percent = 0.0;
  // Largest tabulated PRBM angle up to which |error| stays below the tolerance (follower / dead
  // load); 0 when even the smallest misses it (accuracy_text says so in words).
  double accurate_up_to_deg = 0.0, dead_accurate_up_to_deg = 0.0;
  std::size_t nodes = 0, elements = 0, dofs = 0;
  double element_mm = 0.0, neck_element_mm = 0.0;
  double mesh_seconds = 0.0, solve_seconds = 0.0, linear_solve_seconds = 0.0;
};

// The PRBM's accuracy in words, for the follower (dead_load false) or the dead load: "within 5 %
// up to 15 deg", or, when even the smallest tabulated angle misses the tolerance, "off by more
// than 5 % already at the smallest angle, 2 deg (-7.08 %); within it only at 15, 20 deg" (or
// "; at every angle").
std::string accuracy_text(const PrbmCheckResult& result, bool dead_load);

// The check of the case's needle tip and PRBM check specs (case/specs/prbm_check_spec.hpp).
// Throws CaseError for a bevel needle or unusable prbm_check keys; PETSc must be initialised.
PrbmCheckResult run_prbm_check(const Case& input);

}  // namespace needlefem::prbm
