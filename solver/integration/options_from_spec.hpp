// The integration stage's spec (case/specs/integration_spec.hpp) as integrator and linear-solver
// options.
#pragma once

#include <string>

#include "case/specs/integration_spec.hpp"
#include "integration/ida_integrator.hpp"
#include "integration/newton_matrix_factor.hpp"

namespace needlefem {

IdaOptions ida_options_from_spec(const IntegrationSpec& spec);
// `prefix` is the PETSc options prefix for command-line overrides (-nf_ksp_type ...).
NewtonMatrixOptions newton_matrix_options_from_spec(const IntegrationSpec& spec, const std::string& prefix = "nf_");

}  // namespace needlefem
