// Global assembly of a small set of tetrahedra into PETSc: the part that the compliant tip's
// statics (prbm_check/tip_statics.hpp) and the needle's elasticity check
// (physics/contact/needle_elasticity.hpp) share.
//
// What it owns:
//   - the elements' reference geometry (physics/elements/tet_element.hpp) over a LOCAL node
//     numbering 0..nodes-1 (the caller maps its mesh nodes onto it: the whole tip mesh, or only
//     the needle region of a scene mesh);
//   - a SeqAIJ matrix of 3 x nodes rows, preallocated from the node adjacency (a dof row couples to
//     the 3 dofs of every node that shares an element with its node), with
//     MAT_KEEP_NONZERO_PATTERN so it can be zeroed and re-assembled after clamping;
//   - the element loop: Σ_e of TetElementKernel's residual and/or stiffness at given nodal
//     displacements, residual added into a Vec, stiffness into the matrix with ADD_VALUES, in
//     element order (callers rely on that order for reproducible round-off);
//   - the clamped dofs: MatZeroRowsColumns with 1 on the diagonal, residual entries set to zero.
//
// Why physics/mechanics: this folder is the one for global assembly into PETSc (its library links
// PETSc and the integration layer); physics/elements is kept free of PETSc on purpose (its
// CMakeLists.txt). The tissue's DAE assembly (mechanics_system.hpp) has viscous state, contact
// and threading of its own and does not use this yet.
#pragma once

#include <cstddef>
#include <vector>

#include <petscmat.h>
#include <petscvec.h>

#include "model/tet_mesh.hpp"
#include "physics/elements/tet_element.hpp"

namespace needlefem::mechanics {

class TetAssembly {
 public:
  // element_nodes: nodes_per_tet local node indices per element, in assembly order; positions:
  // reference position of every local node (metres). clamped_dofs: dofs 3 a + i held at zero.
  // Throws std::runtime_error for a degenerate or inverted element (element_geometry).
  // PETSc must be initialised.
  TetAssembly(int nodes_per_tet, std::vector<int> element_nodes, const std::vector<Point3>& positions,
              std::vector<PetscInt> clamped_dofs);
  ~TetAssembly();
  TetAssembly(const TetAssembly&) = delete;
  TetAssembly& operator=(const TetAssembly&) = delete;

  std::size_t elements() const { return geometry_.size(); }
  std::size_t dofs() const { return dofs_; }
  const int* nodes(std::size_t e) const { return element_nodes_.data() + e * nodes_per_tet_; }
  const elements::ElementGeometry& geometry(std::size_t e) const { return geometry_[e]; }
  Mat matrix() const { return matrix_; }

  // A new sequential vector of dofs() entries; the caller destroys it.
  Vec create_vector() const;

  // Element e's nodal values (3 per node) out of a global array of 3 per local node.
  void gather(std::size_t e, const double* global, double* element) const;

  // With displacement u (dofs() values): adds Σ_e r_e(u) into `residual` (dofs() values, e.g. the
  // caller's -f_ext) unless it is null, then zeroes its clamped entries; unless `with_stiffness` is
  // false, sets the matrix to Σ_e K_e(u) (zeroed first), assembles it and clamps it (identity
  // rows and columns). Returns false at the first inverted element: the residual is then partly
  // summed and the matrix unassembled.
  bool add_elements(const elements::TetElementKernel& kernel, const std::vector<double>& u, double* residual,
                    bool with_stiffness) const;

  // Clamped entries of a residual (or load) array set to zero.
  void clamp_residual(double* residual) const;

 private:
  // Clamped rows and columns of the assembled matrix replaced by the identity.
  void clamp_matrix() const;

  int nodes_per_tet_;
  std::vector<int> element_nodes_;
  std::vector<elements::ElementGeometry> geometry_;
  std::vector<PetscInt> clamped_dofs_;
  std::size_t dofs_;
  Mat matrix_ = nullptr;
};

}  // namespace needlefem::mechanics
