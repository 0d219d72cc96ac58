#include "integration/options_from_spec.hpp"

namespace needlefem {

IdaOptions ida_options_from_spec(const IntegrationSpec& spec) {
  IdaOptions options;
  options.relative_tolerance = spec.relative_tolerance;
  options.absolute_tolerance = spec.absolute_tolerance;
  options.max_order = static_cast<int>(spec.max_order);
  options.initial_step = spec.initial_step_s;
  options.max_step = spec.max_step_s;
  options.max_newton_iterations = static_cast<int>(spec.max_newton_iterations);
  options.newton = spec.newton;
  options.newton_convergence_coefficient = spec.newton_convergence_coefficient;
  options.krylov_dimension = static_cast<int>(spec.krylov_dimension);
  options.krylov_tolerance = spec.krylov_tolerance;
  options.krylov_stale_iterations = static_cast<int>(spec.krylov_stale_iterations);
  options.krylov_aged_matrix_ratio = spec.krylov_aged_matrix_ratio;
  options.newton_matrix_cj_change = spec.newton_matrix_cj_change;
  options.suppress_algebraic_error = spec.suppress_algebraic_error;
  options.fixed_step = spec.fixed_step_s;
  return options;
}

NewtonMatrixOptions newton_matrix_options_from_spec(const IntegrationSpec& spec, const std::string& prefix) {
  NewtonMatrixOptions options;
  options.method = spec.linear_solver;
  options.relative_tolerance = spec.linear_relative_tolerance;
  options.prefix = prefix;
  options.preconditioner_only = spec.newton == NewtonMethod::krylov;
  options.symmetric_preconditioner =
      options.preconditioner_only && spec.krylov_preconditioner == KrylovPreconditioner::symmetric;
  return options;
}

}  // namespace needlefem
