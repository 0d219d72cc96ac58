// The case file's [integration] keys (case/schema.cpp) as integrator and linear-solver options.
#pragma once

#include <string>

#include "case/case.hpp"
#include "integration/ida_integrator.hpp"
#include "integration/newton_matrix_factor.hpp"

namespace needlefem {

IdaOptions ida_options_from_case(const Case& c);
// `prefix` is the PETSc options prefix for command-line overrides (-nf_ksp_type ...).
NewtonMatrixOptions newton_matrix_options_from_case(const Case& c, const std::string& prefix = "nf_");

}  // namespace needlefem
