// The [integration] case keys reach the integrator and linear-solver options, with defaults.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "case/case.hpp"
#include "integration/case_options.hpp"

namespace needlefem {
namespace {

TEST(IntegrationCaseOptions, DefaultsAreIdaDefaultsAndSparseCholesky) {
  const Case c = Case::parse("", "defaults");
  const IdaOptions ida = ida_options_from_case(c);
  EXPECT_DOUBLE_EQ(ida.relative_tolerance, 1e-4);
  EXPECT_DOUBLE_EQ(ida.absolute_tolerance, 1e-8);
  EXPECT_EQ(ida.max_order, 5);
  EXPECT_EQ(ida.max_newton_iterations, 20);  // not IDA's 4: contact kinks need more (schema.cpp)
  EXPECT_FALSE(ida.fixed_step.has_value());
  const NewtonMatrixOptions newton = newton_matrix_options_from_case(c);
  EXPECT_EQ(newton.method, "cholesky");
  EXPECT_EQ(newton.prefix, "nf_");
  // Newton-Krylov: the factor only preconditions (single-precision solves), with the exact matrix.
  EXPECT_TRUE(newton.preconditioner_only);
  EXPECT_FALSE(newton.symmetric_preconditioner);
}

// "cholmod", the sparse Cholesky's former name, still selects it, in the file and in overrides.
TEST(IntegrationCaseOptions, FormerCholmodNameReadsAsCholesky) {
  const auto method = [](const std::string& toml, const std::vector<std::string>& overrides) {
    return newton_matrix_options_from_case(Case::parse(toml, "inline", overrides)).method;
  };
  EXPECT_EQ(method("[integration]\nlinear_solver = \"cholmod\"\n", {}), "cholesky");
  EXPECT_EQ(method("", {"integration.linear_solver=cholmod"}), "cholesky");
  EXPECT_EQ(method("", {"integration.linear_solver=mumps"}), "mumps");
}

TEST(IntegrationCaseOptions, SymmetricPreconditionerOnlyWhereTheMatrixPreconditions) {
  const NewtonMatrixOptions krylov =
      newton_matrix_options_from_case(Case::parse("[integration]\nkrylov_preconditioner = \"symmetric\"\n", "inline"));
  EXPECT_TRUE(krylov.preconditioner_only);
  EXPECT_TRUE(krylov.symmetric_preconditioner);
  // Modified Newton solves with the matrix itself: neither applies.
  const NewtonMatrixOptions modified = newton_matrix_options_from_case(Case::parse(
      "[integration]\nkrylov_preconditioner = \"symmetric\"\nnewton = \"modified\"\n", "inline"));
  EXPECT_FALSE(modified.preconditioner_only);
  EXPECT_FALSE(modified.symmetric_preconditioner);
}

TEST(IntegrationCaseOptions, GivenKeysAndOverridesAreUsed) {
  const Case c = Case::parse(
      "[integration]\nrelative_tolerance = 1e-6\nmax_order = 2\nfixed_step_s = 0.005\n"
      "linear_solver = \"gmres-gamg\"\nsuppress_algebraic_error = true\nnewton = \"modified\"\n",
      "inline", {"integration.max_newton_iterations=7"});
  const IdaOptions ida = ida_options_from_case(c);
  EXPECT_DOUBLE_EQ(ida.relative_tolerance, 1e-6);
  EXPECT_EQ(ida.max_order, 2);
  ASSERT_TRUE(ida.fixed_step.has_value());
  EXPECT_DOUBLE_EQ(*ida.fixed_step, 0.005);
  EXPECT_TRUE(ida.suppress_algebraic_error);
  EXPECT_EQ(ida.max_newton_iterations, 7);
  EXPECT_EQ(newton_matrix_options_from_case(c).method, "gmres-gamg");
  EXPECT_EQ(ida.newton, NewtonMethod::modified);
  EXPECT_THROW(Case::parse("[integration]\nlinear_solver = \"pardiso\"\n", "inline"), CaseError);
  // Fixed steps with the default Newton-Krylov: one error naming the key.
  EXPECT_THROW(ida_options_from_case(Case::parse("[integration]\nfixed_step_s = 0.005\n", "inline")), CaseError);
}

}  // namespace
}  // namespace needlefem
