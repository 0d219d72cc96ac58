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
// The system holds `blocks_per_rank` independent material points on each rank of `comm`
// (y = blocks of (sigma, alpha_1, alpha_2)); point k (global) is strained to (k + 1) eps0, so
// every block has its own exact solution. One point on PETSC_COMM_SELF by default.
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
  explicit MaxwellSolidSystem(const MaxwellSolid& solid = {}, const KspOptions& linear_solver = {},
                              MPI_Comm comm = PETSC_COMM_SELF, PetscInt blocks_per_rank = 1)
      : solid_(solid), solver_(comm, linear_solver), blocks_(blocks_per_rank) {
    const PetscInt n = 3 * blocks_;
    petsc_check(MatCreateAIJ(comm, n, n, PETSC_DETERMINE, PETSC_DETERMINE, 3, nullptr, 0, nullptr, &jacobian_),
                "MatCreateAIJ");
    petsc_check(MatGetOwnershipRange(jacobian_, &first_row_, nullptr), "MatGetOwnershipRange");
  }
  ~MaxwellSolidSystem() override { MatDestroy(&jacobian_); }

  // The material point of local block b (its strain amplitude scaled by its global index + 1).
  MaxwellSolid point(PetscInt b) const {
    MaxwellSolid p = solid_;
    p.eps0 *= static_cast<double>(first_row_ / 3 + b + 1);
    return p;
  }
  const MaxwellSolid& solid() const { return solid_; }
  PetscInt blocks() const { return blocks_; }
  long jacobian_setups() const { return setups_; }
  long jacobian_solves() const { return solves_; }

  PetscInt local_size() const override { return 3 * blocks_; }
  long linear_iterations() const override { return solver_.iterations(); }
  bool iterative_linear_solver() const override { return solver_.is_iterative(); }

  void initial_state(double t0, Vec y, Vec ydot) override {
    for_each_block(y, ydot, nullptr, [&](PetscInt b, double* v, double* r, double*) {
      const MaxwellSolid p = point(b);
      const auto y0 = p.exact(t0);
      std::copy(y0.begin(), y0.end(), v);
      // sigma' = (E_inf + sum E_i) eps' - sum E_i alpha_i', alpha_i' = (eps - alpha_i) / tau_i.
      r[1] = (p.strain(t0) - y0[1]) / p.tau[0];
      r[2] = (p.strain(t0) - y0[2]) / p.tau[1];
      r[0] = (p.e_inf + p.e_branch[0] + p.e_branch[1]) * p.strain_rate(t0) - p.e_branch[0] * r[1] -
             p.e_branch[1] * r[2];
    });
  }

  void differential_mask(Vec id) override {
    for_each_block(id, nullptr, nullptr, [](PetscInt, double* v, double*, double*) {
      v[0] = 0.0;
      v[1] = v[2] = 1.0;
    });
  }

  DaeStatus residual(double t, Vec y, Vec ydot, Vec F) override {
    for_each_block(y, ydot, F, [&](PetscInt b, double* v, double* r, double* f) {
      const MaxwellSolid p = point(b);
      const double eps = p.strain(t);
      f[0] = v[0] - p.e_inf * eps - p.e_branch[0] * (eps - v[1]) - p.e_branch[1] * (eps - v[2]);
      f[1] = r[1] - (eps - v[1]) / p.tau[0];
      f[2] = r[2] - (eps - v[2]) / p.tau[1];
    });
    return DaeStatus::ok;
  }

  DaeStatus setup_jacobian(double, Vec, Vec, double cj) override {
    ++setups_;
    for (PetscInt b = 0; b < blocks_; ++b) {
      const PetscInt rows[3] = {first_row_ + 3 * b, first_row_ + 3 * b + 1, first_row_ + 3 * b + 2};
      const double values[9] = {1.0, solid_.e_branch[0], solid_.e_branch[1],  //
                                0.0, cj + 1.0 / solid_.tau[0], 0.0,           //
                                0.0, 0.0, cj + 1.0 / solid_.tau[1]};
      petsc_check(MatSetValues(jacobian_, 3, rows, 3, rows, values, INSERT_VALUES), "MatSetValues");
    }
    petsc_check(MatAssemblyBegin(jacobian_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    petsc_check(MatAssemblyEnd(jacobian_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    return solver_.factor(jacobian_) ? DaeStatus::ok : DaeStatus::recoverable;
  }

  DaeStatus solve_jacobian(Vec b, Vec x) override {
    ++solves_;
    return solver_.solve(b, x) ? DaeStatus::ok : DaeStatus::recoverable;
  }

 private:
  // Calls visit(block, y, y', F) with pointers to the block's three entries of each given
  // vector (nullptr for a vector not needed).
  template <class Visit>
  void for_each_block(Vec first, Vec second, Vec third, Visit visit) const {
    double *a = nullptr, *b = nullptr, *c = nullptr;
    petsc_check(VecGetArray(first, &a), "VecGetArray");
    if (second) petsc_check(VecGetArray(second, &b), "VecGetArray");
    if (third) petsc_check(VecGetArray(third, &c), "VecGetArray");
    for (PetscInt k = 0; k < blocks_; ++k) visit(k, a + 3 * k, b ? b + 3 * k : nullptr, c ? c + 3 * k : nullptr);
    if (third) petsc_check(VecRestoreArray(third, &c), "VecRestoreArray");
    if (second) petsc_check(VecRestoreArray(second, &b), "VecRestoreArray");
    petsc_check(VecRestoreArray(first, &a), "VecRestoreArray");
  }

  MaxwellSolid solid_;
  KspSolver solver_;
  PetscInt blocks_;
  Mat jacobian_ = nullptr;
  PetscInt first_row_ = 0;
  long setups_ = 0;
  long solves_ = 0;
};

}  // namespace needlefem::testing
