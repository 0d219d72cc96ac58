// Global assembly of tetrahedra into PETSc; what and why in tet_assembly.hpp.
#include "physics/mechanics/tet_assembly.hpp"

#include <algorithm>
#include <atomic>

#include <omp.h>

#include "integration/petsc_session.hpp"

namespace needlefem::mechanics {

TetAssembly::TetAssembly(int nodes_per_tet, std::vector<int> element_blocks, const std::vector<Point3>& positions,
                         std::vector<PetscInt> clamped_dofs)
    : nodes_per_tet_(nodes_per_tet),
      element_blocks_(std::move(element_blocks)),
      clamped_dofs_(std::move(clamped_dofs)),
      dofs_(3 * positions.size()) {
  const std::size_t count = element_blocks_.size() / nodes_per_tet_;
  std::vector<double> coordinates(3 * nodes_per_tet_);
  geometry_.reserve(count);
  for (std::size_t e = 0; e < count; ++e) {
    for (int a = 0; a < nodes_per_tet_; ++a)
      for (int i = 0; i < 3; ++i) coordinates[3 * a + i] = positions[blocks(e)[a]][i];
    geometry_.push_back(elements::element_geometry(nodes_per_tet_, coordinates.data()));
  }
  create_matrix(positions.size());
}

TetAssembly::~TetAssembly() { MatDestroy(&matrix_); }

void TetAssembly::create_matrix(std::size_t blocks) {
  const int n = nodes_per_tet_;
  // Block (node) sparsity: blocks sharing an element, sorted per block row.
  std::vector<std::vector<PetscInt>> neighbours(blocks);
  for (std::size_t e = 0; e < elements(); ++e)
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) neighbours[this->blocks(e)[a]].push_back(this->blocks(e)[b]);
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  std::vector<PetscInt> row_start(dofs_ + 1, 0), columns;
  for (std::size_t block = 0; block < blocks; ++block)
    for (int i = 0; i < 3; ++i)
      row_start[3 * block + i + 1] = row_start[3 * block + i] + 3 * static_cast<PetscInt>(neighbours[block].size());
  columns.reserve(static_cast<std::size_t>(row_start.back()));
  for (std::size_t block = 0; block < blocks; ++block)
    for (int i = 0; i < 3; ++i)
      for (const PetscInt column_block : neighbours[block])
        for (int j = 0; j < 3; ++j) columns.push_back(3 * column_block + j);
  const auto size = static_cast<PetscInt>(dofs_);
  petsc_check(MatCreate(PETSC_COMM_SELF, &matrix_), "MatCreate");
  petsc_check(MatSetSizes(matrix_, size, size, size, size), "MatSetSizes");
  petsc_check(MatSetType(matrix_, MATSEQAIJ), "MatSetType");
  petsc_check(MatSetBlockSize(matrix_, 3), "MatSetBlockSize");
  petsc_check(MatSeqAIJSetPreallocationCSR(matrix_, row_start.data(), columns.data(), nullptr),
              "MatSeqAIJSetPreallocationCSR");
  petsc_check(MatSetOption(matrix_, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE), "MatSetOption");
  value_positions_.resize(elements() * static_cast<std::size_t>(3 * n * n));
  for (std::size_t e = 0; e < elements(); ++e)
    for (int a = 0; a < n; ++a) {
      const int block = this->blocks(e)[a];
      const auto& list = neighbours[block];
      for (int b = 0; b < n; ++b) {
        const PetscInt offset = 3 * (std::lower_bound(list.begin(), list.end(), this->blocks(e)[b]) - list.begin());
        for (int i = 0; i < 3; ++i) value_positions_[(e * n + a) * 3 * n + 3 * b + i] = row_start[3 * block + i] + offset;
      }
    }
}

Vec TetAssembly::create_vector() const {
  Vec v = nullptr;
  petsc_check(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(dofs_), &v), "VecCreateSeq");
  petsc_check(VecZeroEntries(v), "VecZeroEntries");
  return v;
}

void TetAssembly::gather(std::size_t e, const double* global, double* element) const {
  const int* element_blocks = blocks(e);
  for (int a = 0; a < nodes_per_tet_; ++a)
    for (int i = 0; i < 3; ++i) element[3 * a + i] = global[3 * element_blocks[a] + i];
}

void TetAssembly::sum_over_elements(std::size_t count, double* out, std::size_t size, const SummedBody& body) const {
#pragma omp parallel
  {
#pragma omp single
    thread_sums_.resize(static_cast<std::size_t>(omp_get_num_threads()) - 1);  // implicit barrier
    const auto thread = static_cast<std::size_t>(omp_get_thread_num());
    double* target = out;
    if (thread > 0) {
      thread_sums_[thread - 1].assign(size, 0.0);
      target = thread_sums_[thread - 1].data();
    }
#pragma omp for schedule(static)
    for (std::size_t e = 0; e < count; ++e) body(e, target);
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < size; ++i)
      for (const auto& copy : thread_sums_) out[i] += copy[i];
  }
}

bool TetAssembly::assemble_elements(const ElementEvaluation& evaluate, double* residual, bool with_matrix) {
  const int n = nodes_per_tet_;
  PetscScalar* values = nullptr;
  if (with_matrix) {
    petsc_check(MatZeroEntries(matrix_), "MatZeroEntries");
    petsc_check(MatSeqAIJGetArray(matrix_, &values), "MatSeqAIJGetArray");
  }
  std::atomic<bool> inverted = false;
  constexpr std::size_t kBatch = 1024;
  std::vector<elements::ElementResult> batch(std::min(kBatch, elements()));
  for (std::size_t first = 0; first < elements() && !inverted; first += kBatch) {
    const std::size_t count = std::min(kBatch, elements() - first);
#pragma omp parallel
    {
#pragma omp for schedule(static)
      for (std::size_t e = 0; e < count; ++e) {
        evaluate(first + e, batch[e]);
        if (batch[e].inverted) inverted = true;
      }  // implicit barrier: the batch is complete
      const auto threads = static_cast<std::size_t>(omp_get_num_threads());
      const auto thread = static_cast<std::size_t>(omp_get_thread_num());
      const std::size_t row_begin = dofs_ * thread / threads, row_end = dofs_ * (thread + 1) / threads;
      for (std::size_t e = 0; e < count && !inverted; ++e) {
        const std::size_t k = first + e;
        const int* element_blocks = blocks(k);
        const PetscInt* positions = value_positions_.data() + k * 3 * n * n;
        for (int a = 0; a < n; ++a)
          for (int i = 0; i < 3; ++i) {
            const auto row_index = static_cast<std::size_t>(3 * element_blocks[a] + i);
            if (row_index < row_begin || row_index >= row_end) continue;
            if (residual) residual[row_index] += batch[e].residual[3 * a + i];
            if (!values) continue;
            const double* row = batch[e].stiffness.data() + static_cast<std::size_t>(3 * a + i) * 3 * n;
            for (int b = 0; b < n; ++b) {
              PetscScalar* target = values + positions[(a * n + b) * 3 + i];
              for (int j = 0; j < 3; ++j) target[j] += row[3 * b + j];
            }
          }
      }
    }
  }
  if (values) petsc_check(MatSeqAIJRestoreArray(matrix_, &values), "MatSeqAIJRestoreArray");
  return !inverted;
}

bool TetAssembly::add_elements(const elements::TetElementKernel& kernel, const double* u, double* residual,
                               bool with_stiffness) {
  const bool valid = assemble_elements(
      [&](std::size_t e, elements::ElementResult& result) {
        std::array<double, elements::kMaxElementDofs> element_u{};
        gather(e, u, element_u.data());
        result = kernel.evaluate(geometry_[e], element_u.data(), nullptr, with_stiffness);
      },
      residual, with_stiffness);
  if (!valid) return false;
  if (residual) clamp_residual(residual);
  if (with_stiffness) {
    petsc_check(MatAssemblyBegin(matrix_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    petsc_check(MatAssemblyEnd(matrix_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    clamp_matrix();
  }
  return true;
}

void TetAssembly::clamp_matrix() const {
  petsc_check(MatZeroRowsColumns(matrix_, static_cast<PetscInt>(clamped_dofs_.size()), clamped_dofs_.data(), 1.0,
                                 nullptr, nullptr),
              "MatZeroRowsColumns");
}

void TetAssembly::clamp_residual(double* residual) const {
  for (PetscInt dof : clamped_dofs_) residual[dof] = 0.0;
}

}  // namespace needlefem::mechanics
