// SparseCholesky against independent MUMPS LU solves: on a symmetric matrix with prescribed
// (identity) rows it must equal J⁻¹ b; on an unsymmetric one it must equal the solve with the
// explicitly symmetrised free block and the prescribed columns moved to the right-hand side;
// an indefinite matrix is a failed factorisation; refactoring with new values stays exact. The
// single-precision factorisation agrees with CHOLMOD's double one to single precision, on one
// thread and with subtrees factored on two to four (oversubscribed on a smaller machine); in
// single precision an unsymmetric matrix is factored by LU and solved exactly (to single
// precision); a team smaller than the factor planned for (a nested region here, OMP_THREAD_LIMIT
// in tests/integration/CMakeLists.txt) gives the same solution. NewtonMatrixFactor, above them,
// falls back to MUMPS LU where Cholesky fails and skips Cholesky for the next setups, factors the
// symmetric part (shifted where indefinite) where the LU would not fit in memory, and serves a
// PETSc KSP as its preconditioner.
#include <cmath>
#include <stdexcept>
#include <utility>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <omp.h>
#include <petscksp.h>

#include "integration/ksp_solver.hpp"
#include "integration/newton_matrix_factor.hpp"
#include "integration/petsc_arrays.hpp"
#include "integration/petsc_session.hpp"
#include "integration/sparse_cholesky.hpp"

namespace needlefem {
namespace {

constexpr PetscInt kSide = 12;
constexpr PetscInt kSize = kSide * kSide;

void assemble(Mat A) {
  petsc_check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

// Nine-point stencil on a kSide x kSide grid: `diagonal` on the diagonal, -1 - skew*(j - i)/|j - i|
// to the neighbours (skew = 0: symmetric, SPD for diagonal >= 8).
Mat grid_matrix(double diagonal, double skew) {
  Mat A = nullptr;
  petsc_check(MatCreateSeqAIJ(PETSC_COMM_SELF, kSize, kSize, 9, nullptr, &A), "MatCreateSeqAIJ");
  for (PetscInt i = 0; i < kSide; ++i)
    for (PetscInt j = 0; j < kSide; ++j) {
      const PetscInt row = i * kSide + j;
      for (PetscInt di = -1; di <= 1; ++di)
        for (PetscInt dj = -1; dj <= 1; ++dj) {
          const PetscInt ni = i + di, nj = j + dj;
          if (ni < 0 || ni >= kSide || nj < 0 || nj >= kSide) continue;
          const PetscInt column = ni * kSide + nj;
          const double value = column == row ? diagonal : -1.0 - skew * (column > row ? 1.0 : -1.0);
          petsc_check(MatSetValue(A, row, column, value, INSERT_VALUES), "MatSetValue");
        }
    }
  assemble(A);
  return A;
}

// 27-point stencil on a side^3 grid: 27 on the diagonal, -1 - skew*(column > row ? 1 : -1) to
// each neighbour (skew = 0: SPD).
Mat cube_matrix(PetscInt side, double skew = 0.0) {
  Mat A = nullptr;
  const PetscInt size = side * side * side;
  petsc_check(MatCreateSeqAIJ(PETSC_COMM_SELF, size, size, 27, nullptr, &A), "MatCreateSeqAIJ");
  for (PetscInt i = 0; i < side; ++i)
    for (PetscInt j = 0; j < side; ++j)
      for (PetscInt k = 0; k < side; ++k)
        for (PetscInt di = -1; di <= 1; ++di)
          for (PetscInt dj = -1; dj <= 1; ++dj)
            for (PetscInt dk = -1; dk <= 1; ++dk) {
              const PetscInt ni = i + di, nj = j + dj, nk = k + dk;
              if (ni < 0 || ni >= side || nj < 0 || nj >= side || nk < 0 || nk >= side) continue;
              const PetscInt row = (i * side + j) * side + k, column = (ni * side + nj) * side + nk;
              const double value = row == column ? 27.0 : -1.0 - skew * (column > row ? 1.0 : -1.0);
              petsc_check(MatSetValue(A, row, column, value, INSERT_VALUES), "MatSetValue");
            }
  assemble(A);
  return A;
}

PetscInt rows_of(Mat A) {
  PetscInt rows = 0, columns = 0;
  petsc_check(MatGetSize(A, &rows, &columns), "MatGetSize");
  return rows;
}

// Every 7th unknown prescribed, its row replaced by an identity row (as the mechanics does).
std::vector<char> prescribe_rows(Mat A) {
  const PetscInt size = rows_of(A);
  std::vector<char> prescribed(size, 0);
  std::vector<PetscInt> rows;
  for (PetscInt k = 0; k < size; k += 7) {
    prescribed[k] = 1;
    rows.push_back(k);
  }
  petsc_check(MatSetOption(A, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE), "MatSetOption");
  petsc_check(MatZeroRows(A, static_cast<PetscInt>(rows.size()), rows.data(), 1.0, nullptr, nullptr), "MatZeroRows");
  return prescribed;
}

Vec right_hand_side(PetscInt size = kSize) {
  Vec b = nullptr;
  petsc_check(VecCreateSeq(PETSC_COMM_SELF, size, &b), "VecCreateSeq");
  WriteArray values(b);
  for (PetscInt k = 0; k < size; ++k) values.data()[k] = std::sin(0.37 * k) + 0.5;
  return b;
}

double relative_difference(Vec x, Vec reference) {
  Vec d = nullptr;
  petsc_check(VecDuplicate(x, &d), "VecDuplicate");
  petsc_check(VecWAXPY(d, -1.0, reference, x), "VecWAXPY");
  double nd = 0.0, nr = 0.0;
  petsc_check(VecNorm(d, NORM_2, &nd), "VecNorm");
  petsc_check(VecNorm(reference, NORM_2, &nr), "VecNorm");
  VecDestroy(&d);
  return nd / nr;
}

Vec lu_solve(Mat A, Vec b) {
  KspSolver lu(PETSC_COMM_SELF);
  EXPECT_TRUE(lu.factor(A)) << lu.last_failure();
  Vec x = nullptr;
  petsc_check(VecDuplicate(b, &x), "VecDuplicate");
  EXPECT_TRUE(lu.solve(b, x)) << lu.last_failure();
  return x;
}

Vec cholesky_solve(SparseCholesky& cholesky, Vec b) {
  Vec x = nullptr;
  petsc_check(VecDuplicate(b, &x), "VecDuplicate");
  cholesky.solve(b, x);
  return x;
}

TEST(SparseCholesky, SymmetricMatrixWithPrescribedRowsSolvesExactly) {
  Mat A = grid_matrix(9.0, 0.0);
  SparseCholesky cholesky(prescribe_rows(A));
  ASSERT_TRUE(cholesky.factor(A)) << cholesky.last_failure();
  Vec b = right_hand_side(), reference = lu_solve(A, b), x = cholesky_solve(cholesky, b);
  const double error = relative_difference(x, reference);
  std::printf("symmetric: |x - x_LU| / |x_LU| = %.2e, factor entries %.0f\n", error, cholesky.factor_entries());
  EXPECT_LT(error, 1e-12);
  EXPECT_GT(cholesky.factor_entries(), 0.0);
  // New values, same pattern: the analysis is reused and the solve is exact again.
  for (PetscInt row = 1; row < kSize; row += 7) petsc_check(MatSetValue(A, row, row, 12.0, INSERT_VALUES), "MatSetValue");
  assemble(A);
  ASSERT_TRUE(cholesky.factor(A));
  Vec reference2 = lu_solve(A, b), x2 = cholesky_solve(cholesky, b);
  EXPECT_LT(relative_difference(x2, reference2), 1e-12);
  EXPECT_GT(relative_difference(reference2, reference), 1e-3);  // the values did change the answer
  EXPECT_EQ(cholesky.factorizations(), 2);
  for (Vec v : {b, reference, x, reference2, x2}) VecDestroy(&v);
  MatDestroy(&A);
}

// The single-precision solve (for preconditioning) agrees with LU to single precision: well
// below the 1e-5 of a preconditioner's needs, and well above double precision's round-off (it
// really is the float copy that solves).
TEST(SparseCholesky, SinglePrecisionSolveAgreesToSinglePrecision) {
  Mat A = grid_matrix(9.0, 0.0);
  SparseCholesky cholesky(prescribe_rows(A), SparseCholesky::Precision::single_precision);
  ASSERT_TRUE(cholesky.factor(A)) << cholesky.last_failure();
  Vec b = right_hand_side(), reference = lu_solve(A, b), x = cholesky_solve(cholesky, b);
  const double error = relative_difference(x, reference);
  std::printf("single-precision solves: |x - x_LU| / |x_LU| = %.2e\n", error);
  EXPECT_LT(error, 1e-5);
  EXPECT_GT(error, 1e-10);
  for (Vec v : {b, reference, x}) VecDestroy(&v);
  MatDestroy(&A);
}

// A 3-D matrix large enough for many supernodes and for root separators whose solves the threads
// share: the single-precision factor (one thread, then two to four threads with concurrent
// subtrees) against CHOLMOD's double-precision one.
TEST(SparseCholesky, SinglePrecisionFactorOnOneToFourThreadsAgreesWithDouble) {
  constexpr PetscInt kCubeSide = 22;
  Mat A = cube_matrix(kCubeSide);
  const std::vector<char> prescribed = prescribe_rows(A);
  Vec b = right_hand_side(rows_of(A));
  SparseCholesky exact(prescribed);
  ASSERT_TRUE(exact.factor(A)) << exact.last_failure();
  Vec reference = cholesky_solve(exact, b);
  const int threads_before = omp_get_max_threads();
  std::vector<Vec> solutions;
  for (int threads : {1, 2, 3, 4}) {
    omp_set_num_threads(threads);  // the subtrees are planned at the first factor()
    SparseCholesky single(prescribed, SparseCholesky::Precision::single_precision);
    ASSERT_TRUE(single.factor(A)) << single.last_failure();
    ASSERT_TRUE(single.factor(A)) << single.last_failure();  // refactoring starts from zero again
    solutions.push_back(cholesky_solve(single, b));
    const double error = relative_difference(solutions.back(), reference);
    std::printf("single-precision factor, %d thread(s), %d concurrent subtrees, %d shared in the solves: "
                "|x - x_double| / |x_double| = %.2e\n",
                threads, single.concurrent_subtrees(), single.shared_solve_supernodes(), error);
    EXPECT_LT(error, 1e-5);
    EXPECT_GT(error, 1e-10);  // it really is single precision
    EXPECT_EQ(single.concurrent_subtrees() > 1, threads > 1);
    EXPECT_EQ(single.shared_solve_supernodes() > 0, threads > 1);
  }
  omp_set_num_threads(threads_before);
  for (Vec x : solutions) EXPECT_LT(relative_difference(x, solutions.front()), 1e-5);
  for (Vec v : solutions) VecDestroy(&v);
  for (Vec v : {b, reference}) VecDestroy(&v);
  MatDestroy(&A);
}

// Two unknowns per point of cube_matrix's grid, each coupled like cube_matrix(side), and the
// pair at a point by [[0, rotation], [-rotation, 0]]: its symmetric part stays cube_matrix's
// (SPD), but for rotation > 27 each point's block [[27, r], [-r, 27]] needs a row exchange to
// be factored stably, as friction's sliding blocks do. With `pairs_as_blocks` the matrix has
// block size 2 (the two unknowns of a point), as the mechanics' has 3.
Mat paired_cube_matrix(PetscInt side, double rotation, bool pairs_as_blocks = false) {
  Mat scalar = cube_matrix(side), A = nullptr;
  const PetscInt size = rows_of(scalar);
  petsc_check(MatCreate(PETSC_COMM_SELF, &A), "MatCreate");
  petsc_check(MatSetSizes(A, 2 * size, 2 * size, 2 * size, 2 * size), "MatSetSizes");
  petsc_check(MatSetType(A, MATSEQAIJ), "MatSetType");
  if (pairs_as_blocks) petsc_check(MatSetBlockSize(A, 2), "MatSetBlockSize");
  petsc_check(MatSeqAIJSetPreallocation(A, 2 * 27, nullptr), "MatSeqAIJSetPreallocation");
  for (PetscInt row = 0; row < size; ++row) {
    PetscInt count = 0;
    const PetscInt* columns = nullptr;
    const PetscScalar* values = nullptr;
    petsc_check(MatGetRow(scalar, row, &count, &columns, &values), "MatGetRow");
    for (PetscInt k = 0; k < count; ++k)
      for (PetscInt half = 0; half < 2; ++half)
        petsc_check(MatSetValue(A, 2 * row + half, 2 * columns[k] + half, values[k], INSERT_VALUES), "MatSetValue");
    petsc_check(MatRestoreRow(scalar, row, &count, &columns, &values), "MatRestoreRow");
    petsc_check(MatSetValue(A, 2 * row, 2 * row + 1, rotation, INSERT_VALUES), "MatSetValue");
    petsc_check(MatSetValue(A, 2 * row + 1, 2 * row, -rotation, INSERT_VALUES), "MatSetValue");
  }
  assemble(A);
  MatDestroy(&scalar);
  return A;
}

// In single precision an unsymmetric free block is factored by LU on the Cholesky structure:
// the solve is J⁻¹ b itself (prescribed rows are identity rows), against MUMPS LU in double, on
// one thread and with subtrees on two to four: a mildly unsymmetric matrix (cube_matrix with skew 0.6,
// diagonally dominant) and one that needs row exchanges (paired_cube_matrix, rotation 40). The
// unsymmetric part changes the answer by far more than the tolerance, and a symmetric matrix
// still takes the Cholesky path.
TEST(SparseCholesky, SinglePrecisionLuOfUnsymmetricMatricesOnOneToFourThreadsAgreesWithMumps) {
  constexpr PetscInt kCubeSide = 16;
  const int threads_before = omp_get_max_threads();
  const auto check_lu = [&](Mat A, Mat symmetric_part, const char* name) {
    const std::vector<char> prescribed = prescribe_rows(A);
    Vec b = right_hand_side(rows_of(A)), reference = lu_solve(A, b);
    for (int threads : {1, 2, 3, 4}) {
      omp_set_num_threads(threads);  // the subtrees are planned at the first factor()
      SparseCholesky single(prescribed, SparseCholesky::Precision::single_precision);
      ASSERT_TRUE(single.factor(A)) << single.last_failure();
      Vec x = cholesky_solve(single, b);
      const double error = relative_difference(x, reference);
      std::printf("single-precision LU, %s, %d thread(s), %d concurrent subtrees, %d shared in the solves: "
                  "|x - x_MUMPS| / |x_MUMPS| = %.2e\n",
                  name, threads, single.concurrent_subtrees(), single.shared_solve_supernodes(), error);
      EXPECT_LT(error, 1e-5);
      EXPECT_GT(error, 1e-10);  // single precision
      EXPECT_EQ(single.lu_factorizations(), 1);
      EXPECT_EQ(single.shared_solve_supernodes() > 0, threads > 1);
      VecDestroy(&x);
    }
    omp_set_num_threads(threads_before);
    prescribe_rows(symmetric_part);
    Vec symmetric_solution = lu_solve(symmetric_part, b);
    const double distance = relative_difference(symmetric_solution, reference);
    std::printf("  (the symmetric matrix's solution is %.2e away)\n", distance);
    EXPECT_GT(distance, 1e-2);
    SparseCholesky single(prescribed, SparseCholesky::Precision::single_precision);
    ASSERT_TRUE(single.factor(symmetric_part)) << single.last_failure();
    EXPECT_EQ(single.lu_factorizations(), 0);
    for (Vec v : {b, reference, symmetric_solution}) VecDestroy(&v);
    MatDestroy(&symmetric_part);
    MatDestroy(&A);
  };
  check_lu(cube_matrix(kCubeSide, 0.6), cube_matrix(kCubeSide), "skew 0.6");
  check_lu(paired_cube_matrix(kCubeSide, 40.0), paired_cube_matrix(kCubeSide, 0.0), "rotation 40");
}

// OpenMP may give a team smaller than the one the factor planned its subtrees for (OMP_THREAD_LIMIT,
// a nested parallel region, dynamic teams). Planned for three threads, then factored and solved
// inside a parallel region where nested regions get one thread: every subtree is still factored
// and the solves' barriers open (one sized for the plan would wait for ever), on an SPD matrix
// (Cholesky) and an unsymmetric one (LU), against MUMPS LU.
TEST(SparseCholesky, SinglePrecisionFactorOnAShorterTeamThanPlannedAgreesWithMumps) {
  constexpr PetscInt kCubeSide = 16;
  const int threads_before = omp_get_max_threads(), levels_before = omp_get_max_active_levels();
  for (const double skew : {0.0, 0.6}) {
    Mat A = cube_matrix(kCubeSide, skew);
    const std::vector<char> prescribed = prescribe_rows(A);
    Vec b = right_hand_side(rows_of(A)), reference = lu_solve(A, b), x = nullptr;
    petsc_check(VecDuplicate(b, &x), "VecDuplicate");
    omp_set_num_threads(3);
    omp_set_max_active_levels(1);
    SparseCholesky single(prescribed, SparseCholesky::Precision::single_precision);
    int team = 0;
    bool factored = false;
#pragma omp parallel num_threads(2)
    if (omp_get_thread_num() == 0) {
#pragma omp parallel num_threads(3)
#pragma omp single
      team = omp_get_num_threads();
      factored = single.factor(A);
      if (factored) single.solve(b, x);
    }
    omp_set_max_active_levels(levels_before);
    omp_set_num_threads(threads_before);
    ASSERT_LT(team, 3) << "no shorter team provoked";
    ASSERT_TRUE(factored) << single.last_failure();
    const double error = relative_difference(x, reference);
    std::printf("single precision, skew %.1f, planned for 3 threads, a team of %d: %d concurrent subtrees, "
                "|x - x_MUMPS| / |x_MUMPS| = %.2e\n",
                skew, team, single.concurrent_subtrees(), error);
    EXPECT_GT(single.concurrent_subtrees(), 1);  // the plan was for several threads
    EXPECT_EQ(single.lu_factorizations(), skew > 0.0 ? 1 : 0);
    EXPECT_LT(error, 1e-5);
    for (Vec v : {b, reference, x}) VecDestroy(&v);
    MatDestroy(&A);
  }
}

// A matrix with a block size is ordered by nested dissection of its node graph (every 7th
// unknown prescribed, so some nodes keep one free unknown of two): the solve matches MUMPS LU,
// and the factor is no larger than with CHOLMOD's ordering of the unknowns.
TEST(SparseCholesky, BlockMatrixOrderedByItsNodeGraphSolvesAndFillsNoMore) {
  constexpr PetscInt kCubeSide = 14;
  double entries[2] = {0.0, 0.0};
  for (bool blocks : {false, true}) {
    Mat A = paired_cube_matrix(kCubeSide, 0.0, blocks);
    const std::vector<char> prescribed = prescribe_rows(A);
    Vec b = right_hand_side(rows_of(A)), reference = lu_solve(A, b);
    SparseCholesky cholesky(prescribed);
    ASSERT_TRUE(cholesky.factor(A)) << cholesky.last_failure();
    Vec x = cholesky_solve(cholesky, b);
    const double error = relative_difference(x, reference);
    entries[blocks] = cholesky.factor_entries();
    std::printf("%s: %.0f factor entries, |x - x_MUMPS| / |x_MUMPS| = %.2e\n",
                blocks ? "node-graph ordering" : "CHOLMOD's ordering", entries[blocks], error);
    EXPECT_LT(error, 1e-10);
    for (Vec v : {b, reference, x}) VecDestroy(&v);
    MatDestroy(&A);
  }
  EXPECT_LT(entries[1], 1.05 * entries[0]);
}

TEST(SparseCholesky, UnsymmetricMatrixSolvesWithItsSymmetricFreeBlock) {
  Mat A = grid_matrix(9.0, 0.3);
  const std::vector<char> prescribed = prescribe_rows(A);
  SparseCholesky cholesky(prescribed);
  ASSERT_TRUE(cholesky.factor(A)) << cholesky.last_failure();
  Vec b = right_hand_side(), x = cholesky_solve(cholesky, b);

  // Reference: S = (A + Aᵀ)/2 with the prescribed rows and columns zeroed (1 on the diagonal)
  // and b_f - A_fp b_p on the right, solved by MUMPS LU.
  Mat At = nullptr, S = nullptr;
  petsc_check(MatTranspose(A, MAT_INITIAL_MATRIX, &At), "MatTranspose");
  petsc_check(MatDuplicate(A, MAT_COPY_VALUES, &S), "MatDuplicate");
  petsc_check(MatAXPY(S, 1.0, At, DIFFERENT_NONZERO_PATTERN), "MatAXPY");
  petsc_check(MatScale(S, 0.5), "MatScale");
  Vec b_p = nullptr, coupling = nullptr, rhs = nullptr;
  petsc_check(VecDuplicate(b, &b_p), "VecDuplicate");
  petsc_check(VecDuplicate(b, &coupling), "VecDuplicate");
  petsc_check(VecDuplicate(b, &rhs), "VecDuplicate");
  std::vector<PetscInt> rows;
  {
    ReadArray in(b);
    WriteArray p(b_p);
    for (PetscInt k = 0; k < kSize; ++k) {
      p.data()[k] = prescribed[k] ? in.data()[k] : 0.0;
      if (prescribed[k]) rows.push_back(k);
    }
  }
  petsc_check(MatMult(A, b_p, coupling), "MatMult");  // A_fp b_p on free rows
  {
    ReadArray in(b), c(coupling);
    WriteArray r(rhs);
    for (PetscInt k = 0; k < kSize; ++k) r.data()[k] = prescribed[k] ? in.data()[k] : in.data()[k] - c.data()[k];
  }
  petsc_check(MatZeroRowsColumns(S, static_cast<PetscInt>(rows.size()), rows.data(), 1.0, nullptr, nullptr),
              "MatZeroRowsColumns");
  Vec reference = lu_solve(S, rhs);
  const double error = relative_difference(x, reference);
  Vec unsymmetric = lu_solve(A, b);
  const double distance = relative_difference(unsymmetric, reference);
  std::printf("unsymmetric: |x - x_ref| / |x_ref| = %.2e (the exact A^-1 b is %.2e away)\n", error, distance);
  EXPECT_LT(error, 1e-12);
  EXPECT_GT(distance, 1e-3);  // the skew part matters: the test can tell the two apart
  // In single precision with Unsymmetric::symmetric_part (the "symmetric" Krylov preconditioner):
  // the same S_ff solve to single precision, where the default would factor A's free block by LU.
  SparseCholesky symmetric_part(prescribed, SparseCholesky::Precision::single_precision,
                                SparseCholesky::Unsymmetric::symmetric_part);
  ASSERT_TRUE(symmetric_part.factor(A)) << symmetric_part.last_failure();
  EXPECT_EQ(symmetric_part.lu_factorizations(), 0);
  Vec x_single = cholesky_solve(symmetric_part, b);
  const double single_error = relative_difference(x_single, reference);
  std::printf("single precision, symmetric part: |x - x_ref| / |x_ref| = %.2e\n", single_error);
  EXPECT_LT(single_error, 1e-5);
  for (Vec v : {b, x, x_single, b_p, coupling, rhs, reference, unsymmetric}) VecDestroy(&v);
  MatDestroy(&At);
  MatDestroy(&S);
  MatDestroy(&A);
}

TEST(SparseCholesky, IndefiniteMatrixIsAFailedFactorisation) {
  for (const auto precision : {SparseCholesky::Precision::double_precision, SparseCholesky::Precision::single_precision}) {
    Mat A = grid_matrix(1.0, 0.0);  // diagonal 1 against eight -1 neighbours: indefinite
    SparseCholesky cholesky(prescribe_rows(A), precision);
    EXPECT_FALSE(cholesky.factor(A));
    EXPECT_NE(cholesky.last_failure().find("not positive definite"), std::string::npos) << cholesky.last_failure();
    std::printf("indefinite: %s\n", cholesky.last_failure().c_str());
    MatDestroy(&A);
  }
}

TEST(SparseCholesky, UnsymmetricPatternIsRejected) {
  Mat A = nullptr;
  petsc_check(MatCreateSeqAIJ(PETSC_COMM_SELF, 2, 2, 2, nullptr, &A), "MatCreateSeqAIJ");
  petsc_check(MatSetValue(A, 0, 0, 2.0, INSERT_VALUES), "MatSetValue");
  petsc_check(MatSetValue(A, 0, 1, 1.0, INSERT_VALUES), "MatSetValue");
  petsc_check(MatSetValue(A, 1, 1, 2.0, INSERT_VALUES), "MatSetValue");
  assemble(A);
  SparseCholesky cholesky(std::vector<char>(2, 0));
  EXPECT_THROW(cholesky.factor(A), std::invalid_argument);
  MatDestroy(&A);
}

// NewtonMatrixFactor's "cholesky" (double precision): an SPD matrix is factored by Cholesky, an
// indefinite one by MUMPS LU after the failed Cholesky attempt, both solved exactly (against
// MUMPS); the three setups after the indefinite one go straight to LU, the fourth tries Cholesky
// again.
TEST(NewtonMatrixFactor, IndefiniteMatrixFallsBackToLuAndSkipsCholeskyForThreeSetups) {
  Mat spd = grid_matrix(9.0, 0.0), indefinite = grid_matrix(1.0, 0.0);
  const std::vector<char> prescribed = prescribe_rows(spd);
  prescribe_rows(indefinite);
  NewtonMatrixFactor factor(prescribed, {.method = LinearSolver::cholesky});
  Vec b = right_hand_side();
  const auto solve_error = [&](Mat A) {
    Vec x = nullptr, reference = lu_solve(A, b);
    petsc_check(VecDuplicate(b, &x), "VecDuplicate");
    EXPECT_TRUE(factor.solve(b, x));
    const double error = relative_difference(x, reference);
    for (Vec v : {x, reference}) VecDestroy(&v);
    return error;
  };
  const auto expect_counts = [&](long cholesky, long ksp) {
    EXPECT_EQ(factor.factorisations().cholesky, cholesky);
    EXPECT_EQ(factor.factorisations().lu, 0);
    EXPECT_EQ(factor.factorisations().ksp, ksp);
  };
  ASSERT_TRUE(factor.factor(spd));
  EXPECT_LT(solve_error(spd), 1e-12);
  expect_counts(1, 0);
  ASSERT_TRUE(factor.factor(indefinite));
  EXPECT_LT(solve_error(indefinite), 1e-12);
  expect_counts(2, 1);  // the failed attempt counts
  for (int setup = 0; setup < 3; ++setup) ASSERT_TRUE(factor.factor(spd));
  EXPECT_LT(solve_error(spd), 1e-12);
  expect_counts(2, 4);
  ASSERT_TRUE(factor.factor(spd));
  EXPECT_LT(solve_error(spd), 1e-12);
  expect_counts(3, 4);
  VecDestroy(&b);
  MatDestroy(&indefinite);
  MatDestroy(&spd);
}

// FGMRES preconditioned by `factor` (attach_to) to a relative residual of 1e-12, at most 200
// iterations: its converged reason and iterations.
std::pair<KSPConvergedReason, PetscInt> preconditioned_gmres(NewtonMatrixFactor& factor, Mat A, Vec b, Vec x) {
  KSP ksp = nullptr;
  PC pc = nullptr;
  petsc_check(KSPCreate(PETSC_COMM_SELF, &ksp), "KSPCreate");
  petsc_check(KSPSetType(ksp, KSPFGMRES), "KSPSetType");
  petsc_check(KSPGMRESSetRestart(ksp, 200), "KSPGMRESSetRestart");
  petsc_check(KSPGetPC(ksp, &pc), "KSPGetPC");
  factor.attach_to(pc);
  petsc_check(KSPSetTolerances(ksp, 1e-12, PETSC_DEFAULT, PETSC_DEFAULT, 200), "KSPSetTolerances");
  petsc_check(KSPSetOperators(ksp, A, A), "KSPSetOperators");
  petsc_check(KSPSolve(ksp, b, x), "KSPSolve");
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  PetscInt iterations = 0;
  petsc_check(KSPGetConvergedReason(ksp, &reason), "KSPGetConvergedReason");
  petsc_check(KSPGetIterationNumber(ksp, &iterations), "KSPGetIterationNumber");
  KSPDestroy(&ksp);
  return {reason, iterations};
}

// Where the LU would not fit in the memory the factor may fill (NewtonMatrixOptions::memory_bytes,
// here 1 byte against 1 TB), an unsymmetric matrix is factored by the Cholesky factor of its
// symmetric part and asks for the symmetric matrix form; FGMRES preconditioned by it still reaches
// MUMPS's solution, in more iterations than with the LU. An indefinite symmetric part (diagonal 5.5
// against eight -1 neighbours: four negative eigenvalues, the smallest -0.92) is factored with a raised diagonal
// instead of by MUMPS, and FGMRES reaches MUMPS's solution of the indefinite matrix with it.
TEST(NewtonMatrixFactor, LuBeyondTheMemoryFactorsTheSymmetricPartAndShiftsAnIndefiniteOne) {
  Mat A = cube_matrix(16, 0.6);
  const std::vector<char> prescribed = prescribe_rows(A);
  Vec b = right_hand_side(rows_of(A)), reference = lu_solve(A, b), x = nullptr;
  petsc_check(VecDuplicate(b, &x), "VecDuplicate");
  PetscInt lu_iterations = 0, symmetric_iterations = 0;
  for (const std::size_t memory : {std::size_t{1} << 40, std::size_t{1}}) {
    NewtonMatrixFactor factor(prescribed,
                              {.method = LinearSolver::cholesky, .preconditioner_only = true, .memory_bytes = memory});
    const auto [reason, iterations] = preconditioned_gmres(factor, A, b, x);
    const double error = relative_difference(x, reference);
    const bool fits = memory > 1;
    std::printf("memory %zu bytes: LU beyond it %d, FGMRES %ld iterations, |x - x_MUMPS| / |x_MUMPS| = %.2e\n", memory,
                factor.factorisations().lu_beyond_memory, static_cast<long>(iterations), error);
    EXPECT_GT(reason, 0);
    EXPECT_LT(error, 1e-10);
    EXPECT_EQ(factor.factorisations().lu_beyond_memory, !fits);
    EXPECT_EQ(factor.wants_symmetric_matrix(), !fits);
    EXPECT_EQ(factor.factorisations().lu, fits ? 1 : 0);
    EXPECT_EQ(factor.factorisations().cholesky, fits ? 0 : 1);
    EXPECT_EQ(factor.factorisations().ksp, 0);
    (fits ? lu_iterations : symmetric_iterations) = iterations;
  }
  EXPECT_GT(symmetric_iterations, lu_iterations);
  for (Vec v : {b, reference, x}) VecDestroy(&v);
  MatDestroy(&A);

  Mat indefinite = grid_matrix(5.5, 0.0);
  const std::vector<char> grid_prescribed = prescribe_rows(indefinite);
  {
    SparseCholesky unshifted(grid_prescribed, SparseCholesky::Precision::single_precision);
    EXPECT_FALSE(unshifted.factor(indefinite));  // the test needs an indefinite symmetric part
  }
  b = right_hand_side();
  reference = lu_solve(indefinite, b);
  petsc_check(VecDuplicate(b, &x), "VecDuplicate");
  NewtonMatrixFactor factor(grid_prescribed,
                            {.method = LinearSolver::cholesky, .preconditioner_only = true, .memory_bytes = 1});
  const auto [reason, iterations] = preconditioned_gmres(factor, indefinite, b, x);
  const double error = relative_difference(x, reference);
  std::printf("indefinite, shifted %ld time(s): FGMRES %ld iterations, |x - x_MUMPS| / |x_MUMPS| = %.2e\n",
              factor.factorisations().shifted, static_cast<long>(iterations), error);
  EXPECT_GT(reason, 0);
  EXPECT_LT(error, 1e-9);
  EXPECT_GE(factor.factorisations().shifted, 1);
  EXPECT_EQ(factor.factorisations().ksp, 0);
  for (Vec v : {b, reference, x}) VecDestroy(&v);
  MatDestroy(&indefinite);
}

// Behind PETSc's preconditioner interface (attach_to): flexible GMRES on an unsymmetric matrix,
// preconditioned by the single-precision LU, reaches a relative residual of 1e-12 in a few
// iterations and MUMPS's solution; a singular matrix, on which Cholesky and then MUMPS fail, is a
// failed preconditioner, which the KSP reports instead of iterating. Flexible GMRES because
// a single-precision solve is linear only to its round-off: plain GMRES's left-preconditioned
// residual estimate then reaches 1e-12 while the error stays at 1e-7.
TEST(NewtonMatrixFactor, AsAShellPreconditionerOfAPetscKsp) {
  Mat A = cube_matrix(16, 0.6);
  const std::vector<char> prescribed = prescribe_rows(A);
  Vec b = right_hand_side(rows_of(A)), reference = lu_solve(A, b), x = nullptr;
  petsc_check(VecDuplicate(b, &x), "VecDuplicate");
  NewtonMatrixFactor single(prescribed, {.method = LinearSolver::cholesky, .preconditioner_only = true});
  const auto [reason, iterations] = preconditioned_gmres(single, A, b, x);
  const double error = relative_difference(x, reference);
  std::printf("FGMRES with the single-precision LU as a shell preconditioner: %ld iterations, |x - x_MUMPS| / "
              "|x_MUMPS| = %.2e\n", static_cast<long>(iterations), error);
  EXPECT_GT(reason, 0);
  EXPECT_LE(iterations, 5);
  EXPECT_LT(error, 1e-10);
  EXPECT_EQ(single.factorisations().lu, 1);
  for (Vec v : {b, reference, x}) VecDestroy(&v);
  MatDestroy(&A);

  Mat singular = nullptr;  // diag(1, 0, 1)
  petsc_check(MatCreateSeqAIJ(PETSC_COMM_SELF, 3, 3, 1, nullptr, &singular), "MatCreateSeqAIJ");
  for (PetscInt row = 0; row < 3; ++row)
    petsc_check(MatSetValue(singular, row, row, row == 1 ? 0.0 : 1.0, INSERT_VALUES), "MatSetValue");
  assemble(singular);
  petsc_check(MatCreateVecs(singular, &x, &b), "MatCreateVecs");
  petsc_check(VecSet(b, 1.0), "VecSet");
  NewtonMatrixFactor exact(std::vector<char>(3, 0), {.method = LinearSolver::cholesky});
  EXPECT_EQ(preconditioned_gmres(exact, singular, b, x).first, KSP_DIVERGED_PC_FAILED);
  for (Vec v : {b, x}) VecDestroy(&v);
  MatDestroy(&singular);
}

}  // namespace
}  // namespace needlefem
