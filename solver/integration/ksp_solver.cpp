#include "integration/ksp_solver.hpp"

#include <fmt/core.h>

#include "integration/petsc_session.hpp"

namespace needlefem {

KspSolver::KspSolver(MPI_Comm comm, const KspOptions& options) {
  petsc_check(KSPCreate(comm, &ksp_), "KSPCreate");
  PC pc = nullptr;
  petsc_check(KSPGetPC(ksp_, &pc), "KSPGetPC");
  if (options.method == KspMethod::mumps) {
    petsc_check(KSPSetType(ksp_, KSPPREONLY), "KSPSetType");
    petsc_check(PCSetType(pc, PCLU), "PCSetType");
    petsc_check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  } else {
    petsc_check(KSPSetType(ksp_, KSPGMRES), "KSPSetType");
    petsc_check(PCSetType(pc, options.method == KspMethod::gmres_gamg ? PCGAMG : PCASM), "PCSetType");
  }
  // Also for MUMPS: a Krylov method chosen on the command line inherits them.
  petsc_check(KSPSetTolerances(ksp_, options.relative_tolerance, PETSC_DEFAULT, PETSC_DEFAULT, options.max_iterations),
              "KSPSetTolerances");
  petsc_check(KSPSetOptionsPrefix(ksp_, options.prefix.c_str()), "KSPSetOptionsPrefix");
  petsc_check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
}

KspSolver::~KspSolver() { KSPDestroy(&ksp_); }

bool KspSolver::is_iterative() const {
  PetscBool direct = PETSC_FALSE;
  petsc_check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(ksp_), KSPPREONLY, &direct),
              "PetscObjectTypeCompare");
  return !direct;
}

bool KspSolver::factor(Mat A) {
  petsc_check(KSPSetOperators(ksp_, A, A), "KSPSetOperators");
  petsc_check(KSPSetUp(ksp_), "KSPSetUp");
  ++factorizations_;
  PC pc = nullptr;
  petsc_check(KSPGetPC(ksp_, &pc), "KSPGetPC");
  PCFailedReason reason = PC_NOERROR;
  petsc_check(PCGetFailedReason(pc, &reason), "PCGetFailedReason");
  if (reason != PC_NOERROR) {
    last_failure_ = fmt::format("preconditioner setup failed: {}", PCFailedReasons[reason]);
    return false;
  }
  return true;
}

bool KspSolver::solve(Vec b, Vec x) {
  petsc_check(KSPSolve(ksp_, b, x), "KSPSolve");
  ++solves_;
  PetscInt its = 0;
  petsc_check(KSPGetIterationNumber(ksp_, &its), "KSPGetIterationNumber");
  if (is_iterative()) iterations_ += its;
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  petsc_check(KSPGetConvergedReason(ksp_, &reason), "KSPGetConvergedReason");
  if (reason < 0) {
    last_failure_ = fmt::format("linear solve failed: {} after {} iterations", KSPConvergedReasons[reason],
                                static_cast<long>(its));
    return false;
  }
  return true;
}

}  // namespace needlefem
