// Equations: condensed_dae_system.hpp.
#include "integration/condensed_dae_system.hpp"

#include "integration/petsc_session.hpp"

namespace needlefem {

CondensedDaeSystem::~CondensedDaeSystem() {
  VecDestroy(&solution_);
  VecDestroy(&rhs_);
}

void CondensedDaeSystem::use_newton_matrix_options(const NewtonMatrixOptions& options) {
  options_ = options;
  factor_.reset();
  factor();  // made here, so that bad solver options stop the run with their own error
}

NewtonMatrixFactor& CondensedDaeSystem::factor() {
  if (!factor_) {
    std::vector<char> prescribed = condensed_prescribed();
    VecDestroy(&solution_);
    VecDestroy(&rhs_);
    petsc_check(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(prescribed.size()), &rhs_), "VecCreateSeq");
    petsc_check(VecDuplicate(rhs_, &solution_), "VecDuplicate");
    factor_ = std::make_unique<NewtonMatrixFactor>(std::move(prescribed), options_);
  }
  return *factor_;
}

DaeStatus CondensedDaeSystem::setup_jacobian(double t, Vec y, Vec ydot, double cj) {
  return guarded([&] {
    NewtonMatrixFactor& f = factor();
    const NewtonMatrix form = f.wants_symmetric_matrix() ? NewtonMatrix::symmetric_preconditioner : NewtonMatrix::exact;
    Mat matrix = nullptr;
    const DaeStatus assembled = assemble_condensed(t, y, ydot, cj, form, matrix);
    if (assembled != DaeStatus::ok) return assembled;
    if (!f.factor(matrix)) {
      ++failures_.factorisations;
      return DaeStatus::recoverable;
    }
    factored_cj_ = cj;
    return DaeStatus::ok;
  });
}

DaeStatus CondensedDaeSystem::solve_jacobian(Vec b, Vec x) {
  return guarded([&] {
    condense(b, factored_cj_, rhs_);
    if (!factor().solve(rhs_, solution_)) {
      ++failures_.solves;
      return DaeStatus::recoverable;
    }
    expand(b, solution_, factored_cj_, x);
    return DaeStatus::ok;
  });
}

void CondensedDaeSystem::accept_step(double t, Vec y, Vec ydot) {
  if (factor_) factor_->step_accepted();
  step_accepted(t, y, ydot);
}

long CondensedDaeSystem::linear_iterations() const { return factor_ ? factor_->iterations() : 0; }

NewtonMatrixFactor::Factorisations CondensedDaeSystem::factorisations() const {
  return factor_ ? factor_->factorisations() : NewtonMatrixFactor::Factorisations{};
}

}  // namespace needlefem
