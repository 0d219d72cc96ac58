// Equations and the measurements behind the choice: sparse_cholesky.hpp.
#include "integration/sparse_cholesky.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <cholmod.h>
#include <metis.h>
#include <omp.h>
#include <fmt/core.h>

#include "integration/blas_threads.hpp"
#include "integration/petsc_arrays.hpp"
#include "integration/petsc_session.hpp"
#include "integration/single_precision_factor.hpp"

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

// Fill-reducing ordering of the free unknowns by METIS nested dissection of the node graph:
// the `block` unknowns of a node (its displacement components) share their couplings, so the
// graph of nodes is a ninth of the unknowns' graph and orders in a fraction of the time; each
// node's free unknowns stay together in the order (CHOLMOD's supernodes merge them anyway).
// On the brain tip it orders faster than CHOLMOD's own choice (AMD, then METIS on the unknowns)
// and gives a factor no larger (docs/speed.md, "Experiments").
// Returns CHOLMOD's permutation of the free unknowns (numbered in order of their rows).
std::vector<int> node_nested_dissection(const RowStructure& structure, const std::vector<PetscInt>& free_index,
                                        PetscInt block) {
  const PetscInt rows = structure.rows();
  const PetscInt* row_start = structure.start();
  const PetscInt* columns = structure.columns();
  // Nodes with a free unknown, and the free unknowns of each (consecutive in free_index).
  std::vector<idx_t> node_index(rows / block, -1), first_free{0};
  std::vector<PetscInt> node_of_vertex;
  for (PetscInt node = 0; node < rows / block; ++node) {
    idx_t free_here = 0;
    for (PetscInt i = node * block; i < (node + 1) * block; ++i) free_here += free_index[i] >= 0;
    if (free_here == 0) continue;
    node_index[node] = static_cast<idx_t>(node_of_vertex.size());
    node_of_vertex.push_back(node);
    first_free.push_back(first_free.back() + free_here);
  }
  idx_t nodes = static_cast<idx_t>(node_of_vertex.size());
  // Nodes v and w are adjacent when a free unknown of v couples to a free unknown of w (the
  // pattern is symmetric, so the graph is).
  std::vector<idx_t> xadj{0}, adjncy, weight(nodes), perm(nodes), iperm(nodes), seen_from(nodes, -1);
  for (idx_t v = 0; v < nodes; ++v) {
    for (PetscInt i = node_of_vertex[v] * block; i < (node_of_vertex[v] + 1) * block; ++i) {
      if (free_index[i] < 0) continue;
      for (PetscInt k = row_start[i]; k < row_start[i + 1]; ++k) {
        if (free_index[columns[k]] < 0) continue;
        const idx_t w = node_index[columns[k] / block];
        if (w == v || seen_from[w] == v) continue;
        seen_from[w] = v;
        adjncy.push_back(w);
      }
    }
    xadj.push_back(static_cast<idx_t>(adjncy.size()));
    weight[v] = first_free[v + 1] - first_free[v];
  }
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 1;  // the same order, factor and rounding in every run
  if (METIS_NodeND(&nodes, xadj.data(), adjncy.data(), weight.data(), options, perm.data(), iperm.data()) != METIS_OK)
    throw std::runtime_error("sparse Cholesky: METIS_NodeND failed on the node graph");
  std::vector<int> order;
  order.reserve(static_cast<std::size_t>(first_free.back()));
  for (idx_t k = 0; k < nodes; ++k)
    for (idx_t u = first_free[perm[k]]; u < first_free[perm[k] + 1]; ++u) order.push_back(static_cast<int>(u));
  return order;
}

void cholmod_check(bool ok, const cholmod_common& common, const char* what) {
  if (!ok || common.status < CHOLMOD_OK)
    throw std::runtime_error(fmt::format("CHOLMOD: {} failed (status {})", what, common.status));
}

}  // namespace

SparseCholesky::SparseCholesky(std::vector<char> prescribed, Precision precision, Unsymmetric unsymmetric)
    : prescribed_(std::move(prescribed)), precision_(precision), unsymmetric_(unsymmetric), common_(new cholmod_common) {
  cholmod_start(common_);
  common_->print = 0;  // failures are reported through status and last_failure()
  // Small or sparse factors would otherwise be simplicial; the single-precision factor is supernodal.
  if (precision_ == Precision::single_precision) common_->supernodal = CHOLMOD_SUPERNODAL;
}

SparseCholesky::~SparseCholesky() {
  release();
  cholmod_finish(common_);
  delete common_;
}

void SparseCholesky::release() {
  single_.reset();
  cholmod_free_factor(&factor_, common_);
  cholmod_free_sparse(&lower_, common_);
  cholmod_free_dense(&rhs_, common_);
  cholmod_free_dense(&solution_, common_);
  cholmod_free_dense(&work_y_, common_);
  cholmod_free_dense(&work_e_, common_);
}

int SparseCholesky::concurrent_subtrees() const { return single_ ? single_->concurrent_subtrees() : 0; }
int SparseCholesky::shared_solve_supernodes() const { return single_ ? single_->shared_solve_supernodes() : 0; }

double SparseCholesky::factor_entries() const { return factor_ ? common_->lnz : 0.0; }

std::size_t SparseCholesky::cholesky_bytes() const { return single_ ? sizeof(float) * factor_->xsize : 0; }

std::size_t SparseCholesky::lu_extra_bytes() const {
  return single_ ? cholesky_bytes() + (2 * sizeof(std::size_t) + sizeof(double)) * entry_.size() : 0;
}

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
  PetscInt block = 1;
  petsc_check(MatGetBlockSize(A, &block), "MatGetBlockSize");
  if (block > 1) {
    std::vector<int> order = node_nested_dissection(structure, free_index_, block);
    common_->nmethods = 1;  // this order only, not also CHOLMOD's own choices
    common_->method[0].ordering = CHOLMOD_GIVEN;
    factor_ = cholmod_analyze_p(lower_, order.data(), nullptr, 0, common_);
    common_->nmethods = 0;  // CHOLMOD's default strategy for a later analysis without blocks
  } else {
    factor_ = cholmod_analyze(lower_, common_);
  }
  cholmod_check(factor_ != nullptr, *common_, "analyze");
  rhs_ = cholmod_zeros(free_count, 1, CHOLMOD_REAL, common_);
  cholmod_check(rhs_ != nullptr, *common_, "zeros");
  if (precision_ == Precision::single_precision) {  // cholmod_solve2 allocates its own at the first solve
    solution_ = cholmod_zeros(free_count, 1, CHOLMOD_REAL, common_);
    cholmod_check(solution_ != nullptr, *common_, "zeros");
    single_ = std::make_unique<SinglePrecisionFactor>();
    single_->analyse(*factor_, *lower_);
  }
  entries_ = row_start[n];
}

bool SparseCholesky::prepare(Mat A) {
  PetscInt rows = 0, columns = 0;
  petsc_check(MatGetSize(A, &rows, &columns), "MatGetSize");
  if (rows != columns || rows != static_cast<PetscInt>(prescribed_.size()))
    throw std::invalid_argument(fmt::format("sparse Cholesky: a {}x{} matrix for {} unknowns", rows, columns,
                                            prescribed_.size()));
  MatInfo info;
  petsc_check(MatGetInfo(A, MAT_LOCAL, &info), "MatGetInfo");
  if (static_cast<PetscInt>(info.nz_used) == entries_) return false;
  analyse(A);
  return true;
}

bool SparseCholesky::factor(Mat A, double diagonal_shift) {
  prepare(A);
  bool unsymmetric = false;
  {
    MatrixValues values(A);
    const double* v = values.data();
    if (precision_ == Precision::single_precision && unsymmetric_ == Unsymmetric::lu) {  // only then is J_ff factored by LU
      double largest = 0.0, skew = 0.0;
      for (std::size_t m = 0; m < entry_.size(); ++m) {
        largest = std::max({largest, std::abs(v[entry_[m]]), std::abs(v[mirror_[m]])});
        skew = std::max(skew, std::abs(v[entry_[m]] - v[mirror_[m]]));
      }
      unsymmetric = skew > kSymmetryTolerance * largest;
    }
    double* x = static_cast<double*>(lower_->x);
    if (unsymmetric) {
      // lower_ holds (J_ji, J_ij) at row j >= column i, J_ij being entry_'s.
      transposed_values_.resize(entry_.size());
      for (std::size_t m = 0; m < entry_.size(); ++m) {
        x[m] = v[mirror_[m]];
        transposed_values_[m] = v[entry_[m]];
      }
    } else {
      for (std::size_t m = 0; m < entry_.size(); ++m) x[m] = 0.5 * (v[entry_[m]] + v[mirror_[m]]);
      if (diagonal_shift > 0.0) {  // each column's first entry is its diagonal (rows sorted, row >= column)
        const int* column_start = static_cast<const int*>(lower_->p);
        const int* row_index = static_cast<const int*>(lower_->i);
        for (int j = 0; j < static_cast<int>(lower_->ncol); ++j)
          if (column_start[j] < column_start[j + 1] && row_index[column_start[j]] == j)
            x[column_start[j]] = (1.0 + diagonal_shift) * std::abs(x[column_start[j]]);
      }
    }
  }
  matrix_ = A;
  ++factorizations_;
  long failed_column = -1;
  if (unsymmetric) {
    ++lu_factorizations_;
    if (!single_->factor_lu(static_cast<const double*>(lower_->x), transposed_values_.data())) {
      last_failure_ = fmt::format("the Newton matrix's single-precision LU found no pivot inside a supernode (free "
                                  "column {} of {})",
                                  single_->failed_column(), static_cast<long>(lower_->ncol));
      return false;
    }
    return true;
  }
  if (precision_ == Precision::single_precision) {
    if (!single_->factor(static_cast<const double*>(lower_->x))) failed_column = single_->failed_column();
  } else {
    // Its large BLAS-3 calls are the work; BLAS is on one thread otherwise (blas_threads.hpp).
    const BlasThreads cores(omp_get_max_threads());
    const int ok = cholmod_factorize(lower_, factor_, common_);
    if (common_->status == CHOLMOD_NOT_POSDEF) failed_column = static_cast<long>(factor_->minor);
    else cholmod_check(ok != 0, *common_, "factorize");
  }
  if (failed_column >= 0) {
    last_failure_ = fmt::format("the Newton matrix's symmetric part is not positive definite (free column {} of {})",
                                failed_column, static_cast<long>(lower_->ncol));
    return false;
  }
  return true;
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
  if (precision_ == Precision::single_precision) {
    single_->solve(static_cast<const double*>(rhs_->x), static_cast<double*>(solution_->x));
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
