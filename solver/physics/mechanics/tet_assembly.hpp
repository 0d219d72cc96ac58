// Global assembly of tetrahedra into PETSc: the one element loop that the tissue's DAE
// (mechanics_system.hpp), the compliant tip's statics (prbm_check/tip_statics.hpp) and the
// needle's elasticity check (physics/contact/needle_elasticity.hpp) share.
//
// What it owns:
//   - the elements' reference geometry (physics/elements/tet_element.hpp) over a block numbering
//     0..blocks-1: block b is one node's three dofs 3 b, 3 b + 1, 3 b + 2 (the caller maps its
//     mesh nodes onto blocks: the tissue's dof map, the whole tip mesh, or only the needle region
//     of a scene mesh);
//   - a SeqAIJ matrix of block size 3 whose pattern is fixed once, as CSR: every row of a block
//     holds the three columns of each block that shares an element with it. Clamped or prescribed
//     rows keep their entries (MAT_KEEP_NONZERO_PATTERN), so a factorisation's symbolic analysis
//     serves every later assembly; element matrices are added straight into the CSR values from
//     the OpenMP threads (MatSetValues is not thread-safe);
//   - the two threaded element loops, both repeatable bit for bit at a given thread count:
//       sum_over_elements: each thread adds its elements into its own copy of the output, the
//         copies then summed in thread order (elements sharing a node never race, without a
//         colouring of the mesh);
//       assemble_elements: batches of elements evaluated on the threads, then added by threads
//         that each own a range of rows, element by element, so every entry (of the matrix and
//         of the residual) sums its elements in element order whatever the thread count;
//   - the clamped dofs of the small problems: rows and columns replaced by the identity,
//     residual entries set to zero.
// Why physics/mechanics: this folder is the one for global assembly into PETSc (its library links
// PETSc and the integration layer); physics/elements is kept free of PETSc on purpose (its
// CMakeLists.txt). The loops take callbacks, not templates, so that they run on the threads of
// this library's OpenMP build wherever they are called from.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include <petscmat.h>
#include <petscvec.h>

#include "model/tet_mesh.hpp"
#include "physics/elements/tet_element.hpp"

namespace needlefem::mechanics {

class TetAssembly {
 public:
  // element_blocks: nodes_per_tet block indices per element, in assembly order; positions:
  // reference position of every block's node (metres). clamped_dofs: dofs 3 b + i held at zero
  // by add_elements and clamp_residual (none for a caller that prescribes its own rows).
  // Throws std::runtime_error for a degenerate or inverted element (element_geometry).
  // PETSc must be initialised.
  TetAssembly(int nodes_per_tet, std::vector<int> element_blocks, const std::vector<Point3>& positions,
              std::vector<PetscInt> clamped_dofs = {});
  ~TetAssembly();
  TetAssembly(const TetAssembly&) = delete;
  TetAssembly& operator=(const TetAssembly&) = delete;

  std::size_t elements() const { return geometry_.size(); }
  std::size_t dofs() const { return dofs_; }
  const int* blocks(std::size_t e) const { return element_blocks_.data() + e * nodes_per_tet_; }
  const elements::ElementGeometry& geometry(std::size_t e) const { return geometry_[e]; }
  Mat matrix() const { return matrix_; }

  // A new sequential vector of dofs() zeros; the caller destroys it.
  Vec create_vector() const;

  // Element e's nodal values (3 per node) out of a global array of 3 per block.
  void gather(std::size_t e, const double* global, double* element) const;

  // body(e, target) for e = 0..count-1 (count <= elements(); 0 runs no body) on the threads,
  // adding element e's contribution into target, an array like `out` (size entries); `out`
  // keeps what it held and receives the sum.
  using SummedBody = std::function<void(std::size_t e, double* target)>;
  void sum_over_elements(std::size_t count, double* out, std::size_t size, const SummedBody& body) const;

  // evaluate(e, result) for every element on the threads, then each result's first 3n residual
  // entries added into `residual` (dofs() values, or null) and, with with_matrix, its stiffness
  // into the matrix's values (zeroed first; not assembled: the caller may add more through
  // MatSetValues, then assembles). Returns false when an element comes back inverted: the sums
  // are then partial.
  using ElementEvaluation = std::function<void(std::size_t e, elements::ElementResult& result)>;
  bool assemble_elements(const ElementEvaluation& evaluate, double* residual, bool with_matrix);

  // With displacement u (dofs() values): adds Σ_e r_e(u) into `residual` (dofs() values, e.g. the
  // caller's -f_ext) unless it is null, then zeroes its clamped entries; unless `with_stiffness` is
  // false, sets the matrix to Σ_e K_e(u), assembles it and clamps it (identity rows and columns).
  // Returns false at an inverted element: the residual is then partly summed and the matrix
  // unassembled.
  bool add_elements(const elements::TetElementKernel& kernel, const double* u, double* residual, bool with_stiffness);

  // Clamped entries of a residual (or load) array set to zero.
  void clamp_residual(double* residual) const;

 private:
  // The CSR pattern and value_positions_, at construction.
  void create_matrix(std::size_t blocks);
  // Clamped rows and columns of the assembled matrix replaced by the identity.
  void clamp_matrix() const;

  int nodes_per_tet_;
  std::vector<int> element_blocks_;
  std::vector<elements::ElementGeometry> geometry_;
  std::vector<PetscInt> clamped_dofs_;
  std::size_t dofs_;
  Mat matrix_ = nullptr;
  // Per element, a, b, i: where entry (3 r_a + i, 3 c_b) of its blocks sits in the matrix's CSR
  // values; the three columns of a block follow it.
  std::vector<PetscInt> value_positions_;
  // sum_over_elements' copies for threads 1, 2, ...: they persist between calls, since pages
  // allocated afresh each call come zeroed from the kernel, which showed in profiles
  // (docs/speed.md, "Measurements formerly in code comments").
  mutable std::vector<std::vector<double>> thread_sums_;
};

}  // namespace needlefem::mechanics
