// Direct solves with a Newton matrix through a sparse Cholesky factorisation of its symmetric
// part on the free unknowns (CHOLMOD, SuiteSparse: Chen, Davis, Hager & Rajamanickam, ACM TOMS
// 35(3):22, 2008; supernodal, BLAS-3). Fill-reducing ordering: METIS nested dissection of the
// node graph when the matrix has a block size (the unknowns of a node), CHOLMOD's choice among
// AMD and METIS on the unknowns otherwise.
//
// J is a PETSc SeqAIJ matrix with a symmetric nonzero pattern whose prescribed (Dirichlet) rows
// may already be identity rows. With f the free and p the prescribed unknowns, solve() returns
//   x_p = b_p,    x_f = S_ff⁻¹ (b_f - J_fp b_p),    S_ff = (J_ff + J_ffᵀ) / 2,
// which is J⁻¹ b exactly when J_ff is symmetric (hyperelastic tangent scaled by a Prony step,
// normal contact penalty). Coulomb friction adds an unsymmetric part: S_ff is then the
// preconditioner of IDA's GMRES rather than an exact inverse.
//
// Why not MUMPS LU on the whole matrix: a Cholesky factor of the symmetric part holds less than
// half the entries of MUMPS's LU (PORD ordering; Debian's MUMPS has no METIS), so it refactors and
// solves faster (the brain-tip figures: docs/speed.md, "What is in place").
//
// The ordering and the symbolic factorisation are computed at the first factor() and reused
// while the matrix keeps its number of entries (its pattern); a changed pattern starts afresh.
//
// Precision::single_precision factors and solves in single precision on CHOLMOD's symbolic
// factor (SinglePrecisionFactor, single_precision_factor.hpp), and (Unsymmetric::lu, the default)
// factors an unsymmetric J_ff (|J_ij - J_ji| above kSymmetryTolerance times its largest entry:
// Coulomb friction) itself by LU on the same structure, so that solve() returns J⁻¹ b, not
// S_ff's: GMRES then gets the exact Newton matrix as its preconditioner at about twice the Cholesky factor's cost instead
// of a pivoting LU's (MUMPS, whose factor has 2.3 times the Cholesky factor's entries). For solves that precondition an
// iteration (IDA's GMRES), not for exact ones: the solution carries a relative error of about
// κ(S_ff) × 6e-8. Why: a solve reads the whole factor twice and is memory-bound, so half the
// bytes take about half the time, and the factorisation's BLAS-3 runs about twice as fast in
// single precision (0.4 mm brain-tip factor, 36.8 M entries: see docs/speed.md).
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <petscmat.h>

struct cholmod_common_struct;
struct cholmod_sparse_struct;
struct cholmod_factor_struct;
struct cholmod_dense_struct;

namespace needlefem {

class SinglePrecisionFactor;

class SparseCholesky {
 public:
  enum class Precision { double_precision, single_precision };
  // What single precision does with an unsymmetric J_ff: LU of J_ff, or Cholesky of S_ff all the
  // same, for a preconditioner kept symmetric on purpose (integration.krylov_preconditioner =
  // "symmetric": friction's pressure coupling left out, the rest of its slip terms unsymmetric).
  enum class Unsymmetric { lu, symmetric_part };
  // prescribed[i] != 0 marks unknown i as given (its row is not factored).
  explicit SparseCholesky(std::vector<char> prescribed, Precision precision = Precision::double_precision,
                          Unsymmetric unsymmetric = Unsymmetric::lu);
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // The ordering and symbolic factorisation of A's pattern, unless it is the one analysed last.
  // Returns whether it analysed (factor() calls it; before it, lu_extra_bytes() can be weighed).
  bool prepare(Mat A);
  // Factor S_ff of A (single precision, unsymmetric J_ff: J_ff by LU). Returns false when S_ff
  // is not positive definite or the LU finds no pivot (last_failure() names the column);
  // throws for a non-square or unsymmetric-pattern matrix and CHOLMOD errors.
  // diagonal_shift > 0 (Cholesky only): S_ff's diagonal entries d_jj are raised to
  // (1 + diagonal_shift) |d_jj| first, a positive definite preconditioner of an indefinite S_ff.
  // A must stay unchanged until the last solve() with this factorisation (J_fp is read there).
  bool factor(Mat A, double diagonal_shift = 0.0);
  // From now on an unsymmetric J_ff is factored as Unsymmetric::symmetric_part says.
  void factor_symmetric_part_only() { unsymmetric_ = Unsymmetric::symmetric_part; }
  // x = J⁻¹ b in the sense above. b and x are sequential vectors of A's size.
  void solve(Vec b, Vec x);

  bool single_precision() const { return precision_ == Precision::single_precision; }
  long factorizations() const { return factorizations_; }  // LU ones included
  long lu_factorizations() const { return lu_factorizations_; }
  // Precision::single_precision: subtrees of the elimination tree factored concurrently by
  // the OpenMP threads (0 on one thread).
  int concurrent_subtrees() const;
  // Single precision: supernodes whose solves the threads share (0 on one thread).
  int shared_solve_supernodes() const;
  // Entries of the last factor L (lower triangle with diagonal).
  double factor_entries() const;
  // Single precision, after prepare(): the bytes of the Cholesky factor's values, and the bytes
  // an LU adds to them (Uᵀ's panels and the positions and values of J_ff's upper triangle).
  std::size_t cholesky_bytes() const;
  std::size_t lu_extra_bytes() const;
  const std::string& last_failure() const { return last_failure_; }

 private:
  void analyse(Mat A);  // ordering, symbolic factorisation and the index maps of A's pattern
  void release();

  std::vector<char> prescribed_;
  std::vector<PetscInt> free_index_;  // per unknown: its index among the free ones, or -1
  PetscInt entries_ = -1;             // the analysed pattern's number of entries
  // For each stored entry of the factored lower triangle: the AIJ positions of J_ij and J_ji.
  std::vector<PetscInt> entry_, mirror_;
  // Free-row / prescribed-column couplings J_fp: AIJ position, free row, prescribed column.
  struct Coupling {
    PetscInt entry, free_row, column;
  };
  std::vector<Coupling> couplings_;
  Mat matrix_ = nullptr;  // the A of the last factor()
  Precision precision_;
  Unsymmetric unsymmetric_;
  std::unique_ptr<SinglePrecisionFactor> single_;  // Precision::single_precision's factor

  cholmod_common_struct* common_ = nullptr;
  cholmod_sparse_struct* lower_ = nullptr;
  cholmod_factor_struct* factor_ = nullptr;
  cholmod_dense_struct *rhs_ = nullptr, *solution_ = nullptr, *work_y_ = nullptr, *work_e_ = nullptr;
  long factorizations_ = 0, lu_factorizations_ = 0;
  std::vector<double> transposed_values_;  // LU: J_ij for lower_'s entry at (j, i), J_ji being in lower_->x
  std::string last_failure_;
  // Relative skew below which J_ff counts as symmetric: element matrices are symmetric to
  // round-off, friction's coupling is of the order of the contact penalty.
  static constexpr double kSymmetryTolerance = 1e-10;
};

}  // namespace needlefem
