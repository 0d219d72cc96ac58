// A DAE system whose Newton matrix the physics condenses onto part of its unknowns, and whose
// condensed matrix the integration stage factors: the physics assembles that matrix and maps
// right-hand sides onto it and solutions back (the tissue: element pressures eliminated element
// by element, mechanics_system.hpp); NewtonMatrixFactor
// (newton_matrix_factor.hpp) chooses how to factor and solve it. So IDA's setup and solve
// (DaeSystem::setup_jacobian, solve_jacobian) are this class's, the same for every such system:
//   setup:  K̂ = assemble_condensed(t, y, y', c_j, form), form as the factor wants it;
//           factor K̂ (the factor's policies and fallbacks);
//   solve:  r = condense(b), x̂ = K̂⁻¹ r, x = expand(b, x̂), both at the factored c_j.
#pragma once

#include <memory>
#include <vector>

#include <petscmat.h>
#include <petscvec.h>

#include "integration/dae_system.hpp"
#include "integration/newton_matrix_factor.hpp"

namespace needlefem {

// What a Newton matrix is for: the exact ∂F/∂y + c_j ∂F/∂y' (modified Newton; the Krylov
// Newton's preconditioner by default), or only the preconditioner of GMRES on the exact
// Jacobian's action, where the physics may leave out terms that spoil the positive definiteness
// of the matrix's symmetric part (penalty_contact.hpp: friction's pressure coupling).
enum class NewtonMatrix { exact, symmetric_preconditioner };

class CondensedDaeSystem : public DaeSystem {
 public:
  CondensedDaeSystem() = default;
  ~CondensedDaeSystem() override;
  CondensedDaeSystem(const CondensedDaeSystem&) = delete;
  CondensedDaeSystem& operator=(const CondensedDaeSystem&) = delete;

  // How the condensed matrix is factored (newton_matrix_options_from_spec: integration.*);
  // NewtonMatrixOptions{} (MUMPS LU) if never called. Makes the factor, so PETSc's errors for
  // bad solver options (-nf_ksp_type ...) come from here; call it before the first setup.
  void use_newton_matrix_options(const NewtonMatrixOptions& options);

  DaeStatus setup_jacobian(double t, Vec y, Vec ydot, double cj) final;
  DaeStatus solve_jacobian(Vec b, Vec x) final;
  void accept_step(double t, Vec y, Vec ydot) final;
  long linear_iterations() const final;

  // How the Newton matrices were factored, and the setups and solves that failed (IDA then cut
  // its step).
  NewtonMatrixFactor::Factorisations factorisations() const;
  struct FactorFailures {
    long factorisations = 0;  // the factor could not factor the condensed matrix
    long solves = 0;          // ... or solve with it
  };
  const FactorFailures& factor_failures() const { return failures_; }

 protected:
  // The condensed unknowns: their number and which of them are prescribed (identity rows).
  virtual std::vector<char> condensed_prescribed() const = 0;
  // The condensed Newton matrix at (t, y, y') and c_j, of the given form, prescribed rows
  // identity rows; keeps what condense and expand need. Returns recoverable for a state that a
  // smaller step may cure (an inverted element), the matrix then not to be factored.
  virtual DaeStatus assemble_condensed(double t, Vec y, Vec ydot, double cj, NewtonMatrix form, Mat& matrix) = 0;
  // The condensed right-hand side of J x = b, and x from b and the condensed system's solution,
  // with the condensation of the last assembly, factored at c_j = cj.
  virtual void condense(Vec b, double cj, Vec condensed_rhs) = 0;
  virtual void expand(Vec b, Vec condensed_solution, double cj, Vec x) = 0;
  // The integrator accepted a step (DaeSystem::accept_step): systems with history update it.
  virtual void step_accepted(double /*t*/, Vec /*y*/, Vec /*ydot*/) {}

 private:
  NewtonMatrixFactor& factor();

  NewtonMatrixOptions options_;
  std::unique_ptr<NewtonMatrixFactor> factor_;  // made at the first use, from options_
  double factored_cj_ = 0.0;
  FactorFailures failures_;
  Vec rhs_ = nullptr, solution_ = nullptr;  // condensed
};

}  // namespace needlefem
