// Equations and the measurements behind the choice: sparse_cholesky.hpp.
#include "integration/sparse_cholesky.hpp"

#include <algorithm>
#include <stdexcept>

#include <cholmod.h>
#include <fmt/core.h>

#include "integration/petsc_arrays.hpp"
#include "integration/petsc_session.hpp"

namespace needlefem {

namespace {

// The CSR arrays of a SeqAIJ matrix, borrowed for a scope.
class RowStructure {
 public:
  explicit RowStructure(Mat A) : A_(A) {
    PetscBool done = PETSC_FALSE;
    petsc_check(MatGetRowIJ(A_, 0, PETSC_FALSE, PETSC_FALSE, &rows_, &start_, &columns_, &done), "MatGetRowIJ");
    if (!done) throw std::invalid_argument("sparse Cholesky: the matrix has no row structure (not SeqAIJ)");
  }
  ~RowStructure() {
    PetscBool done = PETSC_FALSE;
    MatRestoreRowIJ(A_, 0, PETSC_FALSE, PETSC_FALSE, &rows_, &start_, &columns_, &done);
  }
  RowStructure(const RowStructure&) = delete;
  RowStructure& operator=(const RowStructure&) = delete;
  PetscInt rows() const { return rows_; }
  const PetscInt* start() const { return start_; }
  const PetscInt* columns() const { return columns_; }

 private:
  Mat A_;
  PetscInt rows_ = 0;
  const PetscInt* start_ = nullptr;
  const PetscInt* columns_ = nullptr;
};

class MatrixValues {
 public:
  explicit MatrixValues(Mat A) : A_(A) { petsc_check(MatSeqAIJGetArrayRead(A_, &values_), "MatSeqAIJGetArrayRead"); }
  ~MatrixValues() { MatSeqAIJRestoreArrayRead(A_, &values_); }
  MatrixValues(const MatrixValues&) = delete;
  MatrixValues& operator=(const MatrixValues&) = delete;
  const double* data() const { return values_; }

 private:
  Mat A_;
  const PetscScalar* values_ = nullptr;
};

extern "C" {
void strsv_(const char* uplo, const char* trans, const char* diag, const int* n, const float* a, const int* lda,
            float* x, const int* incx);
void sgemv_(const char* trans, const int* m, const int* n, const float* alpha, const float* a, const int* lda,
            const float* x, const int* incx, const float* beta, float* y, const int* incy);
}

void cholmod_check(bool ok, const cholmod_common& common, const char* what) {
  if (!ok || common.status < CHOLMOD_OK)
    throw std::runtime_error(fmt::format("CHOLMOD: {} failed (status {})", what, common.status));
}

}  // namespace

SparseCholesky::SparseCholesky(std::vector<char> prescribed, Precision precision)
    : prescribed_(std::move(prescribed)), precision_(precision), common_(new cholmod_common) {
  cholmod_start(common_);
  common_->print = 0;  // failures are reported through status and last_failure()
  // Small or sparse factors would otherwise be simplicial; the single-precision solve walks supernodes.
  if (precision_ == Precision::single_solves) common_->supernodal = CHOLMOD_SUPERNODAL;
}

SparseCholesky::~SparseCholesky() {
  release();
  cholmod_finish(common_);
  delete common_;
}

void SparseCholesky::release() {
  cholmod_free_factor(&factor_, common_);
  cholmod_free_sparse(&lower_, common_);
  cholmod_free_dense(&rhs_, common_);
  cholmod_free_dense(&solution_, common_);
  cholmod_free_dense(&work_y_, common_);
  cholmod_free_dense(&work_e_, common_);
}

double SparseCholesky::factor_entries() const { return factor_ ? common_->lnz : 0.0; }

void SparseCholesky::analyse(Mat A) {
  const RowStructure structure(A);
  const PetscInt* row_start = structure.start();
  const PetscInt* columns = structure.columns();
  release();
  const auto n = static_cast<PetscInt>(prescribed_.size());
  free_index_.assign(n, -1);
  PetscInt free_count = 0;
  for (PetscInt i = 0; i < n; ++i)
    if (!prescribed_[i]) free_index_[i] = free_count++;

  // The lower triangle of S_ff by columns is the upper triangle of J_ff by rows.
  entry_.clear();
  mirror_.clear();
  couplings_.clear();
  std::vector<int> column_start{0};
  std::vector<int> row_index;
  for (PetscInt i = 0; i < n; ++i) {
    if (prescribed_[i]) continue;
    for (PetscInt k = row_start[i]; k < row_start[i + 1]; ++k) {
      const PetscInt j = columns[k];
      if (prescribed_[j]) {
        couplings_.push_back({k, free_index_[i], j});
        continue;
      }
      if (j < i) continue;
      const PetscInt* row_j_begin = columns + row_start[j];
      const PetscInt* row_j_end = columns + row_start[j + 1];
      const PetscInt* found = std::lower_bound(row_j_begin, row_j_end, i);
      if (found == row_j_end || *found != i)
        throw std::invalid_argument(
            fmt::format("sparse Cholesky: the matrix pattern is not symmetric (entry {},{} without {},{})", i, j, j, i));
      entry_.push_back(k);
      mirror_.push_back(static_cast<PetscInt>(found - columns));
      row_index.push_back(static_cast<int>(free_index_[j]));
    }
    column_start.push_back(static_cast<int>(row_index.size()));
  }
  lower_ = cholmod_allocate_sparse(free_count, free_count, row_index.size(), /*sorted=*/1, /*packed=*/1,
                                   /*stype=*/-1, CHOLMOD_REAL, common_);
  cholmod_check(lower_ != nullptr, *common_, "allocate_sparse");
  std::copy(column_start.begin(), column_start.end(), static_cast<int*>(lower_->p));
  std::copy(row_index.begin(), row_index.end(), static_cast<int*>(lower_->i));
  factor_ = cholmod_analyze(lower_, common_);
  cholmod_check(factor_ != nullptr, *common_, "analyze");
  rhs_ = cholmod_zeros(free_count, 1, CHOLMOD_REAL, common_);
  cholmod_check(rhs_ != nullptr, *common_, "zeros");
  if (precision_ == Precision::single_solves) {  // cholmod_solve2 allocates its own at the first solve
    solution_ = cholmod_zeros(free_count, 1, CHOLMOD_REAL, common_);
    cholmod_check(solution_ != nullptr, *common_, "zeros");
    single_work_.resize(free_count);
    single_gather_.resize(factor_->maxesize);
  }
  entries_ = row_start[n];
}

bool SparseCholesky::factor(Mat A) {
  PetscInt rows = 0, columns = 0;
  petsc_check(MatGetSize(A, &rows, &columns), "MatGetSize");
  if (rows != columns || rows != static_cast<PetscInt>(prescribed_.size()))
    throw std::invalid_argument(fmt::format("sparse Cholesky: a {}x{} matrix for {} unknowns", rows, columns,
                                            prescribed_.size()));
  MatInfo info;
  petsc_check(MatGetInfo(A, MAT_LOCAL, &info), "MatGetInfo");
  if (static_cast<PetscInt>(info.nz_used) != entries_) analyse(A);
  {
    MatrixValues values(A);
    double* x = static_cast<double*>(lower_->x);
    for (std::size_t m = 0; m < entry_.size(); ++m) x[m] = 0.5 * (values.data()[entry_[m]] + values.data()[mirror_[m]]);
  }
  matrix_ = A;
  ++factorizations_;
  const int ok = cholmod_factorize(lower_, factor_, common_);
  if (common_->status == CHOLMOD_NOT_POSDEF) {
    last_failure_ = fmt::format("the Newton matrix's symmetric part is not positive definite (free column {} of {})",
                                static_cast<long>(factor_->minor), static_cast<long>(lower_->ncol));
    return false;
  }
  cholmod_check(ok != 0, *common_, "factorize");
  if (precision_ == Precision::single_solves) {
    if (!factor_->is_super || !factor_->is_ll)
      throw std::logic_error("sparse Cholesky: single-precision solves need CHOLMOD's supernodal LLᵀ factor");
    const auto size = static_cast<std::ptrdiff_t>(factor_->xsize);
    const double* values = static_cast<const double*>(factor_->x);
    single_factor_.resize(size);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t k = 0; k < size; ++k) single_factor_[k] = static_cast<float>(values[k]);
  }
  return true;
}

void SparseCholesky::solve_single(const double* r, double* x) {
  const cholmod_factor& L = *factor_;
  const auto n = static_cast<std::size_t>(L.n);
  const int* perm = static_cast<const int*>(L.Perm);
  const int* super = static_cast<const int*>(L.super);
  const int* row_start = static_cast<const int*>(L.pi);
  const int* value_start = static_cast<const int*>(L.px);
  const int* rows = static_cast<const int*>(L.s);
  const auto supernodes = static_cast<int>(L.nsuper);
  float* y = single_work_.data();
  float* gathered = single_gather_.data();
  for (std::size_t k = 0; k < n; ++k) y[k] = static_cast<float>(r[perm[k]]);  // y = P r
  const int one = 1;
  const float plus = 1.0f, minus = -1.0f, zero = 0.0f;
  // Supernode s: columns super[s]..super[s+1]-1, rows rows[pi[s]..pi[s+1]) (its own columns
  // first), values column-major with leading dimension = its row count.
  for (int s = 0; s < supernodes; ++s) {  // L z = y
    const int first = super[s], columns = super[s + 1] - first;
    const int height = row_start[s + 1] - row_start[s], below = height - columns;
    const float* block = single_factor_.data() + value_start[s];
    strsv_("L", "N", "N", &columns, block, &height, y + first, &one);
    if (below == 0) continue;
    sgemv_("N", &below, &columns, &plus, block + columns, &height, y + first, &one, &zero, gathered, &one);
    const int* below_rows = rows + row_start[s] + columns;
    for (int i = 0; i < below; ++i) y[below_rows[i]] -= gathered[i];
  }
  for (int s = supernodes - 1; s >= 0; --s) {  // Lᵀ w = z
    const int first = super[s], columns = super[s + 1] - first;
    const int height = row_start[s + 1] - row_start[s], below = height - columns;
    const float* block = single_factor_.data() + value_start[s];
    if (below > 0) {
      const int* below_rows = rows + row_start[s] + columns;
      for (int i = 0; i < below; ++i) gathered[i] = y[below_rows[i]];
      sgemv_("T", &below, &columns, &minus, block + columns, &height, gathered, &one, &plus, y + first, &one);
    }
    strsv_("L", "T", "N", &columns, block, &height, y + first, &one);
  }
  for (std::size_t k = 0; k < n; ++k) x[perm[k]] = static_cast<double>(y[k]);  // x = Pᵀ w
}

void SparseCholesky::solve(Vec b, Vec x) {
  if (!matrix_) throw std::logic_error("sparse Cholesky: solve() before factor()");
  ReadArray in(b);
  {
    MatrixValues values(matrix_);
    double* r = static_cast<double*>(rhs_->x);
    const auto n = static_cast<PetscInt>(prescribed_.size());
    for (PetscInt i = 0; i < n; ++i)
      if (!prescribed_[i]) r[free_index_[i]] = in.data()[i];
    for (const Coupling& c : couplings_) r[c.free_row] -= values.data()[c.entry] * in.data()[c.column];
  }
  if (precision_ == Precision::single_solves) {
    solve_single(static_cast<const double*>(rhs_->x), static_cast<double*>(solution_->x));
  } else {
    cholmod_check(
        cholmod_solve2(CHOLMOD_A, factor_, rhs_, nullptr, &solution_, nullptr, &work_y_, &work_e_, common_) != 0,
        *common_, "solve2");
  }
  WriteArray out(x);
  const double* s = static_cast<const double*>(solution_->x);
  for (std::size_t i = 0; i < prescribed_.size(); ++i)
    out.data()[i] = prescribed_[i] ? in.data()[i] : s[free_index_[i]];
}

}  // namespace needlefem
