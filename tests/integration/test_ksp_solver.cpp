// KspSolver on the 2-D five-point Laplacian (SPD, n = 20 x 20): each method reproduces a
// manufactured solution, refactoring with an unchanged pattern reuses the symbolic LU, a
// singular matrix is reported as a failed factorisation, and the options prefix works.
#include <cmath>
#include <utility>

#include <gtest/gtest.h>
#include <petscksp.h>

#include "integration/ksp_solver.hpp"
#include "integration/petsc_session.hpp"

namespace needlefem {
namespace {

constexpr PetscInt kSide = 20;
constexpr PetscInt kSize = kSide * kSide;

// Five-point Laplacian with `diagonal` on the diagonal (4 = Dirichlet Laplacian) and -1 off it.
Mat laplacian(double diagonal) {
  Mat A = nullptr;
  petsc_check(MatCreateSeqAIJ(PETSC_COMM_SELF, kSize, kSize, 5, nullptr, &A), "MatCreateSeqAIJ");
  for (PetscInt i = 0; i < kSide; ++i)
    for (PetscInt j = 0; j < kSide; ++j) {
      const PetscInt row = i * kSide + j;
      petsc_check(MatSetValue(A, row, row, diagonal, INSERT_VALUES), "MatSetValue");
      const PetscInt neighbours[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
      for (const auto& n : neighbours)
        if (n[0] >= 0 && n[0] < kSide && n[1] >= 0 && n[1] < kSide)
          petsc_check(MatSetValue(A, row, n[0] * kSide + n[1], -1.0, INSERT_VALUES), "MatSetValue");
    }
  petsc_check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  return A;
}

Vec manufactured_solution() {
  Vec x = nullptr;
  petsc_check(VecCreateSeq(PETSC_COMM_SELF, kSize, &x), "VecCreateSeq");
  for (PetscInt k = 0; k < kSize; ++k) petsc_check(VecSetValue(x, k, std::sin(0.37 * k) + 0.5, INSERT_VALUES), "VecSetValue");
  petsc_check(VecAssemblyBegin(x), "VecAssemblyBegin");
  petsc_check(VecAssemblyEnd(x), "VecAssemblyEnd");
  return x;
}

// ||x - x_exact|| / ||x_exact|| after solving A x = A x_exact.
double solve_error(KspSolver& solver, Mat A) {
  Vec exact = manufactured_solution(), b = nullptr, x = nullptr;
  petsc_check(VecDuplicate(exact, &b), "VecDuplicate");
  petsc_check(VecDuplicate(exact, &x), "VecDuplicate");
  petsc_check(MatMult(A, exact, b), "MatMult");
  EXPECT_TRUE(solver.solve(b, x)) << solver.last_failure();
  double exact_norm = 0, error_norm = 0;
  petsc_check(VecNorm(exact, NORM_2, &exact_norm), "VecNorm");
  petsc_check(VecAXPY(x, -1.0, exact), "VecAXPY");
  petsc_check(VecNorm(x, NORM_2, &error_norm), "VecNorm");
  VecDestroy(&exact);
  VecDestroy(&b);
  VecDestroy(&x);
  return error_norm / exact_norm;
}

PetscLogDouble event_count(const char* event_name) {
  PetscLogEvent event = 0;
  petsc_check(PetscLogEventGetId(event_name, &event), "PetscLogEventGetId");
  PetscEventPerfInfo info{};
  petsc_check(PetscLogEventGetPerfInfo(0, event, &info), "PetscLogEventGetPerfInfo");
  return info.count;
}

TEST(KspSolver, EachMethodSolvesTheLaplacian) {
  Mat A = laplacian(4.0);
  const std::pair<const char*, KspMethod> methods[] = {
      {"mumps", KspMethod::mumps}, {"gmres-gamg", KspMethod::gmres_gamg}, {"gmres-asm", KspMethod::gmres_asm}};
  for (const auto& [name, method] : methods) {
    KspSolver solver(PETSC_COMM_SELF, {.method = method, .relative_tolerance = 1e-12});
    ASSERT_TRUE(solver.factor(A)) << name << ": " << solver.last_failure();
    const double error = solve_error(solver, A);
    EXPECT_LT(error, 1e-9) << name;
    if (method == KspMethod::mumps) {
      EXPECT_FALSE(solver.is_iterative());
      EXPECT_EQ(solver.iterations(), 0);
    } else {
      EXPECT_TRUE(solver.is_iterative());
      EXPECT_GT(solver.iterations(), 0) << name;
    }
    std::printf("%-11s relative error %.2e, Krylov iterations %ld\n", name, error, solver.iterations());
  }
  MatDestroy(&A);
}

TEST(KspSolver, RefactoringWithTheSamePatternReusesTheSymbolicLu) {
  petsc_check(PetscLogDefaultBegin(), "PetscLogDefaultBegin");
  const PetscLogDouble symbolic_before = event_count("MatLUFactorSym");
  const PetscLogDouble numeric_before = event_count("MatLUFactorNum");
  Mat A = laplacian(4.0);
  KspSolver solver(PETSC_COMM_SELF);
  ASSERT_TRUE(solver.factor(A));
  EXPECT_LT(solve_error(solver, A), 1e-12);
  // New values, same nonzero pattern: a Newton matrix at a new state / new cj.
  for (PetscInt row = 0; row < kSize; ++row) petsc_check(MatSetValue(A, row, row, 6.5, INSERT_VALUES), "MatSetValue");
  petsc_check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  ASSERT_TRUE(solver.factor(A));
  EXPECT_LT(solve_error(solver, A), 1e-12);
  EXPECT_EQ(solver.factorizations(), 2);
  EXPECT_EQ(event_count("MatLUFactorSym") - symbolic_before, 1);
  EXPECT_EQ(event_count("MatLUFactorNum") - numeric_before, 2);
  MatDestroy(&A);
}

TEST(KspSolver, SingularMatrixIsAFailedFactorisationNotACrash) {
  Mat A = nullptr;
  petsc_check(MatCreateSeqAIJ(PETSC_COMM_SELF, 3, 3, 1, nullptr, &A), "MatCreateSeqAIJ");
  for (PetscInt row = 0; row < 3; ++row) petsc_check(MatSetValue(A, row, row, row == 1 ? 0.0 : 1.0, INSERT_VALUES), "MatSetValue");
  petsc_check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  KspSolver solver(PETSC_COMM_SELF);
  Vec b = nullptr, x = nullptr;
  petsc_check(MatCreateVecs(A, &x, &b), "MatCreateVecs");
  petsc_check(VecSet(b, 1.0), "VecSet");
  const bool usable = solver.factor(A) && solver.solve(b, x);
  EXPECT_FALSE(usable);
  EXPECT_FALSE(solver.last_failure().empty());
  std::printf("singular matrix: %s\n", solver.last_failure().c_str());
  VecDestroy(&b);
  VecDestroy(&x);
  MatDestroy(&A);
}

TEST(KspSolver, CommandLineOptionsOverrideTheMethodThroughThePrefix) {
  petsc_check(PetscOptionsSetValue(nullptr, "-prefixtest_ksp_type", "cg"), "PetscOptionsSetValue");
  petsc_check(PetscOptionsSetValue(nullptr, "-prefixtest_pc_type", "jacobi"), "PetscOptionsSetValue");
  KspSolver solver(PETSC_COMM_SELF, {.method = KspMethod::mumps, .prefix = "prefixtest_"});
  EXPECT_TRUE(solver.is_iterative());
  Mat A = laplacian(4.0);
  ASSERT_TRUE(solver.factor(A));
  EXPECT_LT(solve_error(solver, A), 1e-6);
  EXPECT_GT(solver.iterations(), 10);
  MatDestroy(&A);
}

}  // namespace
}  // namespace needlefem
