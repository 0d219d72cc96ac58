// The integration stage's keys, parsed: [integration], the time integrator's and the Newton
// matrix's options (integration/options_from_spec.hpp turns them into IdaOptions and
// NewtonMatrixOptions) and the absolute tolerances per kind of unknown
// (mechanics::MechanicsSystem::absolute_tolerances, set by run/run_case.cpp).
// Values are in the units their keys name.
#pragma once

#include <optional>

namespace needlefem {

class Case;

// integration.newton: how IDA's Newton iteration solves (integration/ida_integrator.hpp).
enum class NewtonMethod { modified, krylov };
// integration.linear_solver: how the Newton matrix is factored (integration/newton_matrix_factor.hpp).
enum class LinearSolver { cholesky, mumps, gmres_gamg, gmres_asm };
// integration.krylov_preconditioner: the matrix that preconditions GMRES with newton = krylov.
enum class KrylovPreconditioner { exact, symmetric };

struct IntegrationSpec {
  double relative_tolerance;
  double absolute_tolerance;  // of the displacements, m
  double pressure_absolute_tolerance_pa;
  long max_order;
  double initial_step_s;  // 0: IDA chooses
  double max_step_s;      // 0: unbounded
  long max_newton_iterations;
  NewtonMethod newton;
  long krylov_dimension;
  long krylov_stale_iterations;
  double krylov_aged_matrix_ratio;
  double krylov_tolerance;
  KrylovPreconditioner krylov_preconditioner;
  double newton_convergence_coefficient;
  double newton_matrix_cj_change;
  bool suppress_algebraic_error;
  std::optional<double> fixed_step_s;  // absent: adaptive steps
  LinearSolver linear_solver;
  double linear_relative_tolerance;
};

// The case's [integration] table. Throws CaseError (integration.fixed_step_s) for fixed steps
// with newton = "krylov".
IntegrationSpec parse_integration_spec(const Case& c);

// The key's name of the choice ("cholesky", "gmres-gamg", ...), for people: what summary.json
// reports as "linear_solver".
const char* linear_solver_name(LinearSolver solver);

}  // namespace needlefem
