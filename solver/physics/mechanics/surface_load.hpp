// Extra terms a boundary surface adds to the tissue's displacement equations (contact, surface
// tractions): MechanicsSystem calls every registered SurfaceLoad after the internal forces.
//   F_u += r_s(t, u, u')            (r_s = -f_ext: minus the surface's nodal forces on the tissue)
//   J   += ∂r_s/∂u + c_j ∂r_s/∂u'
// Prescribed (Dirichlet) rows are overwritten afterwards, so a load may write into them freely.
// Couplings must stay inside one tissue element (e.g. between the nodes of one boundary face):
// the Newton matrix keeps the sparsity of the tet mesh.
#pragma once

#include <petscmat.h>

#include "integration/condensed_dae_system.hpp"
#include "physics/mechanics/dof_map.hpp"

namespace needlefem::mechanics {

class SurfaceLoad {
 public:
  virtual ~SurfaceLoad() = default;
  // y and ydot are the displacement parts of the state (dof numbering of `dofs`).
  virtual void add_residual(double t, const double* y, const double* ydot, const DofMap& dofs, double* f_u) const = 0;
  // Adds 3 x 3 node blocks with MatSetValuesBlocked (block index = node_dof / 3, ADD_VALUES).
  virtual void add_jacobian(double t, const double* y, const double* ydot, double cj, const DofMap& dofs,
                            Mat jacobian, NewtonMatrix form) const = 0;
  // Called once per step the integrator accepts, with its state: loads with history (friction
  // anchors) update it here. Residuals in between see the history of the last accepted step.
  virtual void accept_step(double /*t*/, const double* /*y*/, const double* /*ydot*/, const DofMap& /*dofs*/) {}
  // True if ∂r_s/∂u' is not zero: the Newton matrix then depends on c_j through this load.
  virtual bool depends_on_rates() const = 0;
};

}  // namespace needlefem::mechanics
