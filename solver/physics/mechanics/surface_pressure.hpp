// A pressure p(t) on boundary surfaces of the tissue (mesh scene: groups.pressure), as a surface
// load (surface_load.hpp). Faces are oriented outward of the tissue (model/read_msh.hpp), so
// the traction on the tissue is t = -p n: a positive pressure pushes into the tissue.
// With the face parametrised by the reference triangle (ξ, η), TRI3/TRI6 shape functions N_a
// and the current positions x = Σ N_a x_a (Bonet & Wood, Nonlinear Continuum Mechanics, §8.4):
//   follower (on the deformed area along the deformed normal, n da = x_ξ × x_η dξ dη):
//     r_a = -f_a = p ∫ N_a (x_ξ × x_η) dξ dη,
//     ∂r_a/∂x_b = p ∫ N_a (∂N_b/∂η [x_ξ]× - ∂N_b/∂ξ [x_η]×) dξ dη
//       ([v]× w = v × w; from d(x_ξ × x_η) = -[x_η]× dx_ξ + [x_ξ]× dx_η), not symmetric per face;
//   dead (on the reference area along the reference normal): the same with X for x, and no
//     Newton-matrix term.
// Integrated with the 6-point degree-4 rule of elements/triangle_face.hpp, exact here: on TRI6
// N_a is quadratic and x_ξ, x_η linear, so every integrand is a polynomial of degree 4.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "model/tet_mesh.hpp"
#include "physics/mechanics/surface_load.hpp"

namespace needlefem::mechanics {

class SurfacePressure final : public SurfaceLoad {
 public:
  // `surfaces` name boundary faces of `mesh` (which must outlive this); pressure(t) in Pa.
  SurfacePressure(const TetMesh& mesh, const std::vector<std::string>& surfaces,
                  std::function<double(double)> pressure, bool follower);

  void add_residual(double t, const double* y, const double* ydot, const DofMap& dofs, double* f_u) const override;
  void add_jacobian(double t, const double* y, const double* ydot, double cj, const DofMap& dofs, Mat jacobian,
                    NewtonMatrix form) const override;
  bool depends_on_rates() const override { return false; }

  double pressure(double t) const { return pressure_(t); }  // Pa, the one applied at time t

 private:
  // x (3m) of face f: reference positions, plus the displacements of y for a follower load.
  void face_positions(std::size_t face, const double* y, const DofMap& dofs, double* x) const;
  // r_a of one face (3m values) and, if jacobian is not null, ∂r_a/∂x_b (3m x 3m, row-major).
  void face_terms(const double* x, double p, double* residual, double* jacobian) const;

  const TetMesh& mesh_;
  std::vector<int> face_nodes_;
  int nodes_per_face_;
  std::function<double(double)> pressure_;
  bool follower_;
};

}  // namespace needlefem::mechanics
