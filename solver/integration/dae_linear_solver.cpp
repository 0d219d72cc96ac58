#include "integration/dae_linear_solver.hpp"

#include <exception>

#include <nvector/nvector_petsc.h>

namespace needlefem {

int to_sundials_code(DaeStatus status) {
  switch (status) {
    case DaeStatus::ok: return 0;
    case DaeStatus::recoverable: return 1;
    case DaeStatus::fatal: return -1;
  }
  return -1;
}

namespace {

// ---- SUNMatrix handle ------------------------------------------------------------------
SUNMatrix_ID handle_id(SUNMatrix) { return SUNMATRIX_CUSTOM; }
// IDA zeroes a direct solver's matrix before each Jacobian call; the system assembles afresh.
int handle_zero(SUNMatrix) { return 0; }
void handle_destroy(SUNMatrix A) { SUNMatFreeEmpty(A); }

// ---- SUNLinearSolver -------------------------------------------------------------------
struct SolverContent {
  DaeCallbackContext* callbacks;
  long iterations_before_solve = 0;
  int last_iterations = 0;
  sunindextype last_flag = SUNLS_SUCCESS;
  // IDA takes the "preconditioned residual" as the correction when an iterative solver
  // reports zero iterations; with an exact factorisation that is the solution itself.
  N_Vector last_solution = nullptr;
};

SolverContent& content(SUNLinearSolver S) { return *static_cast<SolverContent*>(S->content); }

SUNLinearSolver_Type solver_type(SUNLinearSolver S) {
  return content(S).callbacks->system.iterative_linear_solver() ? SUNLINEARSOLVER_MATRIX_ITERATIVE
                                                                : SUNLINEARSOLVER_DIRECT;
}
SUNLinearSolver_ID solver_id(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }
int solver_initialize(SUNLinearSolver S) {
  content(S).last_flag = SUNLS_SUCCESS;
  return SUNLS_SUCCESS;
}
// The factorisation was made by setup_jacobian() in IDA's Jacobian callback just before.
int solver_setup(SUNLinearSolver S, SUNMatrix) {
  content(S).last_flag = SUNLS_SUCCESS;
  return SUNLS_SUCCESS;
}

int solver_solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, realtype) {
  auto& c = content(S);
  DaeSystem& system = c.callbacks->system;
  c.last_solution = x;
  int flag = SUNLS_SUCCESS;
  try {
    c.iterations_before_solve = system.linear_iterations();
    switch (system.solve_jacobian(N_VGetVector_Petsc(b), N_VGetVector_Petsc(x))) {
      case DaeStatus::ok: flag = SUNLS_SUCCESS; break;
      case DaeStatus::recoverable: flag = SUNLS_PACKAGE_FAIL_REC; break;
      case DaeStatus::fatal: flag = SUNLS_PACKAGE_FAIL_UNREC; break;
    }
    c.last_iterations = static_cast<int>(system.linear_iterations() - c.iterations_before_solve);
  } catch (const std::exception& e) {
    c.callbacks->last_exception = e.what();
    flag = SUNLS_PACKAGE_FAIL_UNREC;
  }
  c.last_flag = flag;
  return flag;
}

int solver_iterations(SUNLinearSolver S) { return content(S).last_iterations; }
N_Vector solver_residual(SUNLinearSolver S) { return content(S).last_solution; }
sunindextype solver_last_flag(SUNLinearSolver S) { return content(S).last_flag; }
int solver_free(SUNLinearSolver S) {
  if (!S) return SUNLS_SUCCESS;
  delete static_cast<SolverContent*>(S->content);
  S->content = nullptr;
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}

}  // namespace

SUNMatrix make_jacobian_handle(SUNContext context) {
  SUNMatrix A = SUNMatNewEmpty(context);
  if (!A) return nullptr;
  A->ops->getid = handle_id;
  A->ops->zero = handle_zero;
  A->ops->destroy = handle_destroy;
  return A;
}

SUNLinearSolver make_dae_linear_solver(SUNContext context, DaeCallbackContext& callbacks) {
  SUNLinearSolver S = SUNLinSolNewEmpty(context);
  if (!S) return nullptr;
  S->ops->gettype = solver_type;
  S->ops->getid = solver_id;
  S->ops->initialize = solver_initialize;
  S->ops->setup = solver_setup;
  S->ops->solve = solver_solve;
  S->ops->numiters = solver_iterations;
  S->ops->resid = solver_residual;
  S->ops->lastflag = solver_last_flag;
  S->ops->free = solver_free;
  S->content = new SolverContent{&callbacks};
  return S;
}

}  // namespace needlefem
