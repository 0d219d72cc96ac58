#include "integration/case_options.hpp"

namespace needlefem {

IdaOptions ida_options_from_case(const Case& c) {
  IdaOptions options;
  options.relative_tolerance = c.real("integration.relative_tolerance");
  options.absolute_tolerance = c.real("integration.absolute_tolerance");
  options.max_order = static_cast<int>(c.integer("integration.max_order"));
  options.initial_step = c.real("integration.initial_step_s");
  options.max_step = c.real("integration.max_step_s");
  options.max_newton_iterations = static_cast<int>(c.integer("integration.max_newton_iterations"));
  options.newton = c.text("integration.newton") == "krylov" ? NewtonMethod::krylov : NewtonMethod::modified;
  options.newton_convergence_coefficient = c.real("integration.newton_convergence_coefficient");
  options.krylov_dimension = static_cast<int>(c.integer("integration.krylov_dimension"));
  options.krylov_tolerance = c.real("integration.krylov_tolerance");
  options.krylov_stale_iterations = static_cast<int>(c.integer("integration.krylov_stale_iterations"));
  options.krylov_aged_matrix_ratio = c.real("integration.krylov_aged_matrix_ratio");
  options.newton_matrix_cj_change = c.real("integration.newton_matrix_cj_change");
  options.suppress_algebraic_error = c.flag("integration.suppress_algebraic_error");
  options.fixed_step = c.maybe_real("integration.fixed_step_s");
  if (options.fixed_step && options.newton == NewtonMethod::krylov)
    throw c.error("integration.fixed_step_s", "fixed steps need integration.newton = \"modified\"");
  return options;
}

NewtonMatrixOptions newton_matrix_options_from_case(const Case& c, const std::string& prefix) {
  NewtonMatrixOptions options;
  options.method = c.text("integration.linear_solver");
  options.relative_tolerance = c.real("integration.linear_relative_tolerance");
  options.prefix = prefix;
  options.preconditioner_only = c.text("integration.newton") == "krylov";
  options.symmetric_preconditioner =
      options.preconditioner_only && c.text("integration.krylov_preconditioner") == "symmetric";
  return options;
}

}  // namespace needlefem
