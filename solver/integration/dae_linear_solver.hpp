// The SUNDIALS objects that route IDA's Newton linear algebra to a DaeSystem.
//
// IDA's matrix-based linear-solver interface calls, when it decides the Newton matrix is
// stale (new step size ratio, convergence failure, every few steps):
//   Jacobian callback (ours, set with IDASetJacFn) -> DaeSystem::setup_jacobian(t, y, y', cj)
//   SUNLinSolSetup                               -> nothing left to do (already factored)
// and, for every Newton iteration,
//   SUNLinSolSolve                               -> DaeSystem::solve_jacobian(b, x).
// The SUNMatrix is a thin handle (getid, zero, destroy): the PETSc matrix and its
// factorisation live inside the DaeSystem. A matrix-EMBEDDED solver type must not be used:
// IDA then skips the setup call entirely (see TOOLCHAIN.md), so the solver reports
// SUNLINEARSOLVER_DIRECT, or SUNLINEARSOLVER_MATRIX_ITERATIVE for a Krylov solve.
#pragma once

#include <string>

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include "integration/dae_system.hpp"

namespace needlefem {

// What every SUNDIALS callback needs: the system, and where to leave the text of an exception
// that was caught at the callback boundary (it becomes part of the integrator's error).
struct DaeCallbackContext {
  DaeSystem& system;
  std::string last_exception;
};

// DaeStatus -> SUNDIALS convention: 0 ok, > 0 recoverable (IDA cuts the step), < 0 fatal.
int to_sundials_code(DaeStatus status);

SUNMatrix make_jacobian_handle(SUNContext context);
SUNLinearSolver make_dae_linear_solver(SUNContext context, DaeCallbackContext& callbacks);

}  // namespace needlefem
