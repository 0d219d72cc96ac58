// Output fields of the tissue at one time, from IDA's state y = (u, Q) and its rate y'
// (physics/mechanics/mechanics_system.hpp): the quantities of point_quantities.hpp at every
// quadrature point of every tissue element, reduced to
//   node fields   displacement u and velocity u' (m, m/s; zero on nodes without tissue dofs),
//   cell fields   the Cauchy stress tensor as the element's VOLUME AVERAGE (Σ_q w_q σ_q / V_e),
//                 every scalar quantity as the MAXIMUM over the element's quadrature points
//                 (what safety limits are checked against; zero on non-tissue cells),
//   maxima        per scalar quantity, the maximum over all tissue quadrature points with that
//                 point's reference position X_q = Σ_a N_a(ξ_q) X_a,
//   point values  every scalar quantity and F at every tissue quadrature point, in the order of
//                 point_positions() and point_volumes() (for the mesh-objective safety
//                 metrics, safety_metrics.hpp),
//   kinetic energy  T = 1/2 ρ ∫ |u'|² dV (the quasi-static model neglects it; reported to show
//                 it is negligible next to the elastic energy).
#pragma once

#include <array>
#include <string>
#include <vector>

#include <petscvec.h>

#include "model/tet_mesh.hpp"
#include "physics/material/tensor.hpp"
#include "physics/mechanics/mechanics_system.hpp"

namespace needlefem::fields {

// The scalar quantities, in this order everywhere (cell arrays, maxima, names).
enum ScalarQuantity {
  kVonMises,
  kMaxPrincipalStress,
  kLogStrain,
  kStrainRate,
  kEquivalentStrainRate,
  kPressure,
  kScalarQuantities
};
struct ScalarQuantityInfo {
  const char* name;         // result.h5 field name; history.csv has its maximum as max_<name>
  const char* unit;
  const char* summary_key;  // its maximum's key under summary.json "max"
};
const std::array<ScalarQuantityInfo, kScalarQuantities>& scalar_quantities();
// history.csv's column of a quantity's maximum over the tissue points.
std::string history_maximum_column(const ScalarQuantityInfo& quantity);

struct PointMaximum {
  double value = 0.0;
  Point3 position{};  // reference position of the quadrature point, metres
};

struct TissueFields {
  std::vector<double> displacement;   // mesh nodes x 3
  std::vector<double> velocity;       // mesh nodes x 3
  std::vector<double> cauchy_stress;  // mesh tets x 6 (xx yy zz xy yz xz), volume average
  std::array<std::vector<double>, kScalarQuantities> cell_maximum;  // mesh tets each
  std::array<PointMaximum, kScalarQuantities> maximum;
  std::array<std::vector<double>, kScalarQuantities> point_value;  // tissue quadrature points each
  std::vector<material::Mat3d> deformation_gradient;              // F at each tissue quadrature point
  double kinetic_energy = 0.0;        // J
};

class TissueFieldEvaluator {
 public:
  // `system` and `mesh` must outlive the evaluator.
  TissueFieldEvaluator(const mechanics::MechanicsSystem& system, const TetMesh& mesh, double density_kg_per_m3);

  // Throws std::runtime_error for an inverted element (the integrator never accepts one).
  TissueFields evaluate(Vec y, Vec ydot) const;

  // The deformation gradient F = I + ∂u/∂X at every tissue quadrature point (in the order of
  // point_positions()), from the displacements in y alone: cheap enough for every accepted step.
  std::vector<material::Mat3d> deformation_gradients(Vec y) const;

  // Per tissue quadrature point (element by element): reference position (m) and reference
  // volume w_q (quadrature weight times det J, m³).
  const std::vector<Point3>& point_positions() const { return point_positions_; }
  const std::vector<double>& point_volumes() const { return point_volumes_; }
  // The straight tetrahedra through each tissue element's vertices (reference positions, m): the
  // region the points fill.
  std::vector<std::array<Point3, 4>> tissue_tetrahedra() const;
  // The barycentric coordinates of an element's points in its tetrahedron, in point order (the
  // quadrature rule's, the same in every element).
  std::vector<std::array<double, 4>> point_barycentric() const;

 private:
  // Node fields filled, every other array sized and zeroed (maxima at -inf).
  TissueFields node_fields(const double* state, const double* rate) const;
  // Tissue element k's point values, cell maxima and mean Cauchy stress into `out`; the first
  // point of each of its maxima into `largest_point` and its kinetic energy added to
  // `kinetic_energy`. False (nothing written) for an inverted element.
  bool evaluate_element(std::size_t k, const double* state, const double* rate, TissueFields& out,
                        std::array<int, kScalarQuantities>& largest_point, double& kinetic_energy) const;

  const mechanics::MechanicsSystem& system_;
  const TetMesh& mesh_;
  double density_;
  std::vector<std::vector<double>> shape_values_;  // per point: N_a(ξ_q)
  std::vector<Point3> point_positions_;            // per tissue element and point
  std::vector<double> point_volumes_;              // per tissue element and point
};

}  // namespace needlefem::fields
