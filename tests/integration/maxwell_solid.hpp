// A closed-form DAE for the integrator tests: a generalised Maxwell (Wiechert) solid under a
// prescribed ramp-and-hold strain, written the way the tissue mechanics writes it: an
// algebraic stress balance plus differential internal (viscous) variables, with the Newton
// matrix assembled into a PETSc AIJ matrix and solved by KspSolver (MUMPS LU by default).
//
//   eps(t)   = eps0 t / t_ramp for t < t_ramp, eps0 after          (prescribed strain)
//   F_0      = sigma - E_inf eps - sum_i E_i (eps - alpha_i) = 0    (algebraic: stress)
//   F_i      = alpha_i' - (eps - alpha_i) / tau_i = 0                (viscous strain of branch i)
//   J        = dF/dy + cj dF/dy' = [[1, E_1, E_2], [0, cj + 1/tau_1, 0], [0, 0, cj + 1/tau_2]]
//
// Closed form (branch stress q_i = E_i (eps - alpha_i) solves q_i' + q_i / tau_i = E_i eps'):
//   ramp (rate r = eps0 / t_ramp): q_i(t) = E_i r tau_i (1 - exp(-t / tau_i))
//   hold:                          q_i(t) = q_i(t_ramp) exp(-(t - t_ramp) / tau_i)
//   sigma = E_inf eps + sum_i q_i,  alpha_i = eps - q_i / E_i.
// Moduli: Miller's brain Prony fractions g = 0.450, 0.365 of a 1 kPa instantaneous modulus,
// with the slow time shortened from 50 s to 5 s to keep the test short.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include <petscmat.h>

#include "integration/dae_system.hpp"
#include "integration/ksp_solver.hpp"
#include "integration/petsc_session.hpp"

namespace needlefem::testing {

struct MaxwellSolid {
  double e_inf = 185.0;                         // Pa
  std::array<double, 2> e_branch{450.0, 365.0};  // Pa
  std::array<double, 2> tau{0.5, 5.0};           // s
  double eps0 = 0.1;
  double t_ramp = 0.1;  // s

  double strain(double t) const { return t < t_ramp ? eps0 * t / t_ramp : eps0; }
  double strain_rate(double t) const { return t < t_ramp ? eps0 / t_ramp : 0.0; }
  double branch_stress(int i, double t) const {
    const double rate = eps0 / t_ramp;
    const double during_ramp = e_branch[i] * rate * tau[i] * (1.0 - std::exp(-std::min(t, t_ramp) / tau[i]));
    return t < t_ramp ? during_ramp : during_ramp * std::exp(-(t - t_ramp) / tau[i]);
  }
  // Exact y = (sigma, alpha_1, alpha_2) at t.
  std::array<double, 3> exact(double t) const {
    const double eps = strain(t);
    const double q1 = branch_stress(0, t), q2 = branch_stress(1, t);
    return {e_inf * eps + q1 + q2, eps - q1 / e_branch[0], eps - q2 / e_branch[1]};
  }
  double peak_stress() const { return exact(t_ramp)[0]; }
};

class MaxwellSolidSystem : public DaeSystem {
 public:
  explicit MaxwellSolidSystem(const MaxwellSolid& solid = {}, const KspOptions& linear_solver = {})
      : solid_(solid), solver_(PETSC_COMM_SELF, linear_solver) {
    petsc_check(MatCreateSeqAIJ(PETSC_COMM_SELF, 3, 3, 3, nullptr, &jacobian_), "MatCreateSeqAIJ");
  }
  ~MaxwellSolidSystem() override { MatDestroy(&jacobian_); }

  const MaxwellSolid& solid() const { return solid_; }
  long jacobian_setups() const { return setups_; }
  long jacobian_solves() const { return solves_; }

  PetscInt local_size() const override { return 3; }
  long linear_iterations() const override { return solver_.iterations(); }
  bool iterative_linear_solver() const override { return solver_.is_iterative(); }

  void initial_state(double t0, Vec y, Vec ydot) override {
    const auto y0 = solid_.exact(t0);
    const double rate = solid_.strain_rate(t0);
    set(y, {y0[0], y0[1], y0[2]});
    // sigma' = (E_inf + sum E_i) eps' - sum E_i alpha_i' at t0 (all alpha' zero from rest).
    set(ydot, {(solid_.e_inf + solid_.e_branch[0] + solid_.e_branch[1]) * rate,
               (solid_.strain(t0) - y0[1]) / solid_.tau[0], (solid_.strain(t0) - y0[2]) / solid_.tau[1]});
  }

  void differential_mask(Vec id) override { set(id, {0.0, 1.0, 1.0}); }

  DaeStatus residual(double t, Vec y, Vec ydot, Vec F) override {
    const auto v = get(y), r = get(ydot);
    const double eps = solid_.strain(t);
    set(F, {v[0] - solid_.e_inf * eps - solid_.e_branch[0] * (eps - v[1]) - solid_.e_branch[1] * (eps - v[2]),
            r[1] - (eps - v[1]) / solid_.tau[0], r[2] - (eps - v[2]) / solid_.tau[1]});
    return DaeStatus::ok;
  }

  DaeStatus setup_jacobian(double, Vec, Vec, double cj) override {
    ++setups_;
    const PetscInt rows[3] = {0, 1, 2};
    const double values[9] = {1.0, solid_.e_branch[0], solid_.e_branch[1],  //
                              0.0, cj + 1.0 / solid_.tau[0], 0.0,           //
                              0.0, 0.0, cj + 1.0 / solid_.tau[1]};
    petsc_check(MatSetValues(jacobian_, 3, rows, 3, rows, values, INSERT_VALUES), "MatSetValues");
    petsc_check(MatAssemblyBegin(jacobian_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    petsc_check(MatAssemblyEnd(jacobian_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    return solver_.factor(jacobian_) ? DaeStatus::ok : DaeStatus::recoverable;
  }

  DaeStatus solve_jacobian(Vec b, Vec x) override {
    ++solves_;
    return solver_.solve(b, x) ? DaeStatus::ok : DaeStatus::recoverable;
  }

 private:
  static void set(Vec v, std::array<double, 3> values) {
    double* a = nullptr;
    petsc_check(VecGetArray(v, &a), "VecGetArray");
    for (int i = 0; i < 3; ++i) a[i] = values[i];
    petsc_check(VecRestoreArray(v, &a), "VecRestoreArray");
  }
  static std::array<double, 3> get(Vec v) {
    const double* a = nullptr;
    petsc_check(VecGetArrayRead(v, &a), "VecGetArrayRead");
    std::array<double, 3> values{a[0], a[1], a[2]};
    petsc_check(VecRestoreArrayRead(v, &a), "VecRestoreArrayRead");
    return values;
  }

  MaxwellSolid solid_;
  KspSolver solver_;
  Mat jacobian_ = nullptr;
  long setups_ = 0;
  long solves_ = 0;
};

}  // namespace needlefem::testing
