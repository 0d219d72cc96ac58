// Global assembly of a small set of tetrahedra into PETSc; what and why in tet_assembly.hpp.
#include "physics/mechanics/tet_assembly.hpp"

#include <set>

#include "integration/petsc_session.hpp"

namespace needlefem::mechanics {

TetAssembly::TetAssembly(int nodes_per_tet, std::vector<int> element_nodes, const std::vector<Point3>& positions,
                         std::vector<PetscInt> clamped_dofs)
    : nodes_per_tet_(nodes_per_tet),
      element_nodes_(std::move(element_nodes)),
      clamped_dofs_(std::move(clamped_dofs)),
      dofs_(3 * positions.size()) {
  const std::size_t count = element_nodes_.size() / nodes_per_tet_;
  std::vector<double> coordinates(3 * nodes_per_tet_);
  geometry_.reserve(count);
  for (std::size_t e = 0; e < count; ++e) {
    for (int a = 0; a < nodes_per_tet_; ++a)
      for (int i = 0; i < 3; ++i) coordinates[3 * a + i] = positions[nodes(e)[a]][i];
    geometry_.push_back(elements::element_geometry(nodes_per_tet_, coordinates.data()));
  }

  // Matrix pattern: dof rows couple to the 3 dofs of every node sharing an element.
  std::vector<std::set<int>> neighbours(positions.size());
  for (std::size_t e = 0; e < count; ++e)
    for (int a = 0; a < nodes_per_tet_; ++a) neighbours[nodes(e)[a]].insert(nodes(e), nodes(e) + nodes_per_tet_);
  std::vector<PetscInt> nonzeros(dofs_);
  for (std::size_t a = 0; a < positions.size(); ++a)
    for (int i = 0; i < 3; ++i) nonzeros[3 * a + i] = static_cast<PetscInt>(3 * neighbours[a].size());
  const auto n = static_cast<PetscInt>(dofs_);
  petsc_check(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 0, nonzeros.data(), &matrix_), "MatCreateSeqAIJ");
  // Clamping keeps the zeroed entries in the pattern, so the next assembly needs no new allocation.
  petsc_check(MatSetOption(matrix_, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE), "MatSetOption");
}

TetAssembly::~TetAssembly() { MatDestroy(&matrix_); }

Vec TetAssembly::create_vector() const {
  Vec v = nullptr;
  petsc_check(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(dofs_), &v), "VecCreateSeq");
  return v;
}

void TetAssembly::gather(std::size_t e, const double* global, double* element) const {
  const int* element_nodes = nodes(e);
  for (int a = 0; a < nodes_per_tet_; ++a)
    for (int i = 0; i < 3; ++i) element[3 * a + i] = global[3 * element_nodes[a] + i];
}

bool TetAssembly::add_elements(const elements::TetElementKernel& kernel, const std::vector<double>& u,
                               double* residual, bool with_stiffness) const {
  if (with_stiffness) petsc_check(MatZeroEntries(matrix_), "MatZeroEntries");
  const int element_dofs = 3 * nodes_per_tet_;
  std::vector<double> element_u(element_dofs);
  std::vector<PetscInt> rows(element_dofs);
  for (std::size_t e = 0; e < elements(); ++e) {
    gather(e, u.data(), element_u.data());
    const elements::ElementResult result = kernel.evaluate(geometry_[e], element_u.data(), nullptr, with_stiffness);
    if (result.inverted) return false;
    for (int a = 0; a < nodes_per_tet_; ++a)
      for (int i = 0; i < 3; ++i) rows[3 * a + i] = 3 * nodes(e)[a] + i;
    if (residual)
      for (int c = 0; c < element_dofs; ++c) residual[rows[c]] += result.residual[c];
    if (with_stiffness)
      petsc_check(MatSetValues(matrix_, element_dofs, rows.data(), element_dofs, rows.data(), result.stiffness.data(),
                               ADD_VALUES),
                  "MatSetValues");
  }
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
