#include "case/specs/integration_spec.hpp"

#include <array>
#include <utility>

#include "case/case.hpp"
#include "case/specs/choice.hpp"

namespace needlefem {

namespace {

// Each key's choices (schema.cpp) with their enumerators.
const std::array kNewtonMethods{std::pair{"modified", NewtonMethod::modified},
                                std::pair{"krylov", NewtonMethod::krylov}};
const std::array kLinearSolvers{std::pair{"cholesky", LinearSolver::cholesky}, std::pair{"mumps", LinearSolver::mumps},
                                std::pair{"gmres-gamg", LinearSolver::gmres_gamg},
                                std::pair{"gmres-asm", LinearSolver::gmres_asm}};
const std::array kKrylovPreconditioners{std::pair{"exact", KrylovPreconditioner::exact},
                                        std::pair{"symmetric", KrylovPreconditioner::symmetric}};

}  // namespace

IntegrationSpec parse_integration_spec(const Case& c) {
  const IntegrationSpec spec{
      .relative_tolerance = c.real("integration.relative_tolerance"),
      .absolute_tolerance = c.real("integration.absolute_tolerance"),
      .pressure_absolute_tolerance_pa = c.real("integration.pressure_absolute_tolerance_pa"),
      .max_order = c.integer("integration.max_order"),
      .initial_step_s = c.real("integration.initial_step_s"),
      .max_step_s = c.real("integration.max_step_s"),
      .max_newton_iterations = c.integer("integration.max_newton_iterations"),
      .newton = parse_choice(c, "integration.newton", kNewtonMethods),
      .krylov_dimension = c.integer("integration.krylov_dimension"),
      .krylov_stale_iterations = c.integer("integration.krylov_stale_iterations"),
      .krylov_aged_matrix_ratio = c.real("integration.krylov_aged_matrix_ratio"),
      .krylov_tolerance = c.real("integration.krylov_tolerance"),
      .krylov_preconditioner = parse_choice(c, "integration.krylov_preconditioner", kKrylovPreconditioners),
      .newton_convergence_coefficient = c.real("integration.newton_convergence_coefficient"),
      .newton_matrix_cj_change = c.real("integration.newton_matrix_cj_change"),
      .suppress_algebraic_error = c.flag("integration.suppress_algebraic_error"),
      .fixed_step_s = c.maybe_real("integration.fixed_step_s"),
      .linear_solver = parse_choice(c, "integration.linear_solver", kLinearSolvers),
      .linear_relative_tolerance = c.real("integration.linear_relative_tolerance"),
  };
  if (spec.fixed_step_s && spec.newton == NewtonMethod::krylov)
    throw c.error("integration.fixed_step_s", "fixed steps need integration.newton = \"modified\"");
  return spec;
}

const char* linear_solver_name(LinearSolver solver) { return choice_name(kLinearSolvers, solver); }

}  // namespace needlefem
