// The [integration] case keys reach the integration spec and from it the integrator and
// linear-solver options, with the schema's defaults.
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "case/case.hpp"
#include "case/specs/integration_spec.hpp"
#include "integration/options_from_spec.hpp"

namespace needlefem {
namespace {

IntegrationSpec spec_of(const std::string& toml, const std::vector<std::string>& overrides = {}) {
  return parse_integration_spec(Case::parse(toml, "inline", overrides));
}

TEST(IntegrationOptionsFromSpec, DefaultsAreIdaDefaultsAndSparseCholesky) {
  const IntegrationSpec spec = spec_of("");
  const IdaOptions ida = ida_options_from_spec(spec);
  EXPECT_DOUBLE_EQ(ida.relative_tolerance, 3e-4);
  EXPECT_DOUBLE_EQ(ida.absolute_tolerance, 3e-8);
  EXPECT_EQ(ida.max_order, 5);
  EXPECT_EQ(ida.max_newton_iterations, 20);  // not IDA's 4: contact kinks need more (schema.cpp)
  EXPECT_FALSE(ida.fixed_step.has_value());
  EXPECT_DOUBLE_EQ(spec.pressure_absolute_tolerance_pa, 0.3);
  const NewtonMatrixOptions newton = newton_matrix_options_from_spec(spec);
  EXPECT_EQ(newton.method, LinearSolver::cholesky);
  EXPECT_EQ(newton.prefix, "nf_");
  // Newton-Krylov: the factor only preconditions (single-precision solves), with the exact matrix.
  EXPECT_TRUE(newton.preconditioner_only);
  EXPECT_FALSE(newton.symmetric_preconditioner);
}

// "cholmod", the sparse Cholesky's former name, still selects it, in the file and in overrides;
// every choice of the key reaches the factor as its own enumerator, and summary.json names it
// under the key's name (linear_solver_name).
TEST(IntegrationOptionsFromSpec, LinearSolverChoicesKeepTheirNames) {
  const auto method = [](const std::string& toml, const std::vector<std::string>& overrides) {
    return newton_matrix_options_from_spec(spec_of(toml, overrides)).method;
  };
  EXPECT_EQ(method("[integration]\nlinear_solver = \"cholmod\"\n", {}), LinearSolver::cholesky);
  EXPECT_EQ(method("", {"integration.linear_solver=cholmod"}), LinearSolver::cholesky);
  const std::pair<std::string, LinearSolver> choices[] = {{"cholesky", LinearSolver::cholesky},
                                                          {"mumps", LinearSolver::mumps},
                                                          {"gmres-gamg", LinearSolver::gmres_gamg},
                                                          {"gmres-asm", LinearSolver::gmres_asm}};
  for (const auto& [name, solver] : choices) {
    EXPECT_EQ(method("", {"integration.linear_solver=" + name}), solver) << name;
    EXPECT_EQ(linear_solver_name(solver), name);
  }
}

TEST(IntegrationOptionsFromSpec, SymmetricPreconditionerOnlyWhereTheMatrixPreconditions) {
  const NewtonMatrixOptions krylov =
      newton_matrix_options_from_spec(spec_of("[integration]\nkrylov_preconditioner = \"symmetric\"\n"));
  EXPECT_TRUE(krylov.preconditioner_only);
  EXPECT_TRUE(krylov.symmetric_preconditioner);
  // Modified Newton solves with the matrix itself: neither applies.
  const NewtonMatrixOptions modified = newton_matrix_options_from_spec(
      spec_of("[integration]\nkrylov_preconditioner = \"symmetric\"\nnewton = \"modified\"\n"));
  EXPECT_FALSE(modified.preconditioner_only);
  EXPECT_FALSE(modified.symmetric_preconditioner);
}

TEST(IntegrationOptionsFromSpec, GivenKeysAndOverridesAreUsed) {
  const IntegrationSpec spec = spec_of(
      "[integration]\nrelative_tolerance = 1e-6\nmax_order = 2\nfixed_step_s = 0.005\n"
      "linear_solver = \"gmres-gamg\"\nsuppress_algebraic_error = true\nnewton = \"modified\"\n"
      "pressure_absolute_tolerance_pa = 0.5\n",
      {"integration.max_newton_iterations=7"});
  const IdaOptions ida = ida_options_from_spec(spec);
  EXPECT_DOUBLE_EQ(ida.relative_tolerance, 1e-6);
  EXPECT_EQ(ida.max_order, 2);
  ASSERT_TRUE(ida.fixed_step.has_value());
  EXPECT_DOUBLE_EQ(*ida.fixed_step, 0.005);
  EXPECT_TRUE(ida.suppress_algebraic_error);
  EXPECT_EQ(ida.max_newton_iterations, 7);
  EXPECT_EQ(newton_matrix_options_from_spec(spec).method, LinearSolver::gmres_gamg);
  EXPECT_EQ(ida.newton, NewtonMethod::modified);
  EXPECT_DOUBLE_EQ(spec.pressure_absolute_tolerance_pa, 0.5);
  EXPECT_THROW(spec_of("[integration]\nlinear_solver = \"pardiso\"\n"), CaseError);
  // Fixed steps with the default Newton-Krylov: one error naming the key, when the case is parsed.
  EXPECT_THROW(spec_of("[integration]\nfixed_step_s = 0.005\n"), CaseError);
}

}  // namespace
}  // namespace needlefem
