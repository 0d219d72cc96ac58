#include "physics/fields/tissue_fields.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "integration/petsc_arrays.hpp"
#include "model/tet_geometry.hpp"
#include "physics/fields/point_quantities.hpp"

namespace needlefem::fields {

const std::array<ScalarQuantityInfo, kScalarQuantities>& scalar_quantities() {
  static const std::array<ScalarQuantityInfo, kScalarQuantities> info{
      {{"von_mises", "Pa", "von_mises_pa"},
       {"max_principal_stress", "Pa", "principal_stress_pa"},
       {"log_strain", "1", "log_strain"},
       {"strain_rate", "1/s", "strain_rate_per_s"},
       {"equivalent_strain_rate", "1/s", "equivalent_strain_rate_per_s"},
       {"pressure", "Pa", "pressure_pa"}}};
  return info;
}

std::string history_maximum_column(const ScalarQuantityInfo& quantity) { return std::string("max_") + quantity.name; }

TissueFieldEvaluator::TissueFieldEvaluator(const mechanics::MechanicsSystem& system, const TetMesh& mesh,
                                           double density_kg_per_m3)
    : system_(system), mesh_(mesh), density_(density_kg_per_m3) {
  const int n = mesh.nodes_per_tet;
  for (const auto& point : elements::element_quadrature(n)) {
    std::vector<double> N(n);
    tet_shape_values(n, point.xi, N.data());
    shape_values_.push_back(std::move(N));
  }
  const auto& tissue_tets = system.dof_map().tissue_tets;
  for (std::size_t k = 0; k < tissue_tets.size(); ++k)
    for (double w : system.geometry(k).weight) point_volumes_.push_back(w);
  for (std::size_t e : tissue_tets)
    for (const auto& N : shape_values_) {
      Point3 X{};
      for (int a = 0; a < n; ++a)
        for (int c = 0; c < 3; ++c) X[c] += N[a] * mesh.nodes[mesh.tet(e)[a]][c];
      point_positions_.push_back(X);
    }
}

TissueFields TissueFieldEvaluator::node_fields(const double* state, const double* rate) const {
  const auto& dofs = system_.dof_map();
  TissueFields out;
  out.displacement.assign(3 * mesh_.nodes.size(), 0.0);
  out.velocity.assign(3 * mesh_.nodes.size(), 0.0);
  for (std::size_t node = 0; node < mesh_.nodes.size(); ++node)
    if (dofs.node_dof[node] >= 0)
      for (int c = 0; c < 3; ++c) {
        out.displacement[3 * node + c] = state[dofs.dof(static_cast<int>(node), c)];
        out.velocity[3 * node + c] = rate[dofs.dof(static_cast<int>(node), c)];
      }
  out.cauchy_stress.assign(6 * mesh_.tet_count(), 0.0);
  for (auto& cells : out.cell_maximum) cells.assign(mesh_.tet_count(), 0.0);
  for (auto& m : out.maximum) m.value = -std::numeric_limits<double>::infinity();
  for (auto& values : out.point_value) values.assign(point_positions_.size(), 0.0);
  out.deformation_gradient.resize(point_positions_.size());
  return out;
}

bool TissueFieldEvaluator::evaluate_element(std::size_t k, const double* state, const double* rate,
                                            TissueFields& out, std::array<int, kScalarQuantities>& largest_point,
                                            double& kinetic_energy) const {
  const auto& dofs = system_.dof_map();
  const int n = mesh_.nodes_per_tet, points = static_cast<int>(shape_values_.size());
  const std::size_t e = dofs.tissue_tets[k];
  std::array<double, elements::kMaxElementDofs> u_e, v_e;
  system_.gather(k, state, u_e.data());
  system_.gather(k, rate, v_e.data());
  // The fields are those of an accepted state, whose viscous stresses the system keeps.
  elements::ViscousStep view;
  const auto& geometry = system_.geometry(k);
  const elements::ElementResult result = system_.kernel().evaluate(
      geometry, u_e.data(), system_.accepted_viscous_state(k, view), false, system_.element_pressure(state, k));
  if (result.inverted) return false;

  const bool mixed = system_.kernel().formulation() == elements::Formulation::mean_dilatation;
  Mat3d average_stress;
  for (int q = 0; q < points; ++q) {
    const double w = geometry.weight[q];
    Mat3d F, F_rate;
    F.a = result.points[q].deformation_gradient;
    out.deformation_gradient[k * points + q] = F;
    elements::add_field_gradient(geometry, q, v_e.data(), F_rate);
    Point3 velocity{};
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < 3; ++i) velocity[i] += shape_values_[q][a] * v_e[3 * a + i];
    kinetic_energy +=
        0.5 * density_ * w * (velocity[0] * velocity[0] + velocity[1] * velocity[1] + velocity[2] * velocity[2]);

    // σ = J⁻¹ F S Fᵀ + p I: S as the element carried it (S_iso - Σ Q_i, or all of S for laws
    // without the split, whose pressure is then 0), p the element's or the point's U'(J).
    const double p = mixed ? result.pressure : result.points[q].pressure;
    const Mat3d stress =
        push_forward(F, material::from_voigt(result.points[q].stress.data())) + Mat3d::diagonal(p, p, p);
    const PointQuantities pq = point_quantities(F, F_rate, stress);
    average_stress += (w / geometry.volume) * stress;

    const std::array<double, kScalarQuantities> values{pq.von_mises,       pq.max_principal_stress,
                                                       pq.max_log_strain,  pq.max_strain_rate,
                                                       pq.equivalent_strain_rate, pq.pressure};
    for (int s = 0; s < kScalarQuantities; ++s) {
      out.point_value[s][k * points + q] = values[s];
      double& cell = out.cell_maximum[s][e];
      if (q == 0 || values[s] > cell) {
        cell = values[s];
        largest_point[s] = q;
      }
    }
  }
  const double vtk_order[6] = {average_stress(0, 0), average_stress(1, 1), average_stress(2, 2),
                               average_stress(0, 1), average_stress(1, 2), average_stress(0, 2)};
  std::copy(vtk_order, vtk_order + 6, out.cauchy_stress.begin() + 6 * e);
  return true;
}

TissueFields TissueFieldEvaluator::evaluate(Vec y, Vec ydot) const {
  const ReadArray state(y), rate(ydot);
  const auto& dofs = system_.dof_map();
  const int points = static_cast<int>(shape_values_.size());
  TissueFields out = node_fields(state.data(), rate.data());

  // The elements run on the OpenMP threads. What crosses elements (the largest value over all
  // points with its position, the kinetic energy) is gathered afterwards in element order, so
  // the fields do not depend on the thread count.
  const std::size_t element_count = dofs.tissue_tets.size();
  std::vector<std::array<int, kScalarQuantities>> largest_point(element_count);  // first point of the element's max
  std::vector<double> element_kinetic_energy(element_count, 0.0);
  std::vector<char> inverted(element_count, 0);
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < element_count; ++k)
    inverted[k] = !evaluate_element(k, state.data(), rate.data(), out, largest_point[k], element_kinetic_energy[k]);
  for (std::size_t k = 0; k < element_count; ++k) {
    const std::size_t e = dofs.tissue_tets[k];
    if (inverted[k]) throw std::runtime_error("output fields: inverted tissue element " + std::to_string(e));
    out.kinetic_energy += element_kinetic_energy[k];
    for (int s = 0; s < kScalarQuantities; ++s)
      if (out.cell_maximum[s][e] > out.maximum[s].value)
        out.maximum[s] = {out.cell_maximum[s][e], point_positions_[k * points + largest_point[k][s]]};
  }
  return out;
}

std::vector<std::array<Point3, 4>> TissueFieldEvaluator::tissue_tetrahedra() const {
  std::vector<std::array<Point3, 4>> out;
  for (std::size_t e : system_.dof_map().tissue_tets) {
    const int* tet = mesh_.tet(e);
    out.push_back({mesh_.nodes[tet[0]], mesh_.nodes[tet[1]], mesh_.nodes[tet[2]], mesh_.nodes[tet[3]]});
  }
  return out;
}

std::vector<std::array<double, 4>> TissueFieldEvaluator::point_barycentric() const {
  std::vector<std::array<double, 4>> out;
  for (const auto& point : elements::element_quadrature(mesh_.nodes_per_tet)) {
    const auto& xi = point.xi;
    out.push_back({1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]});
  }
  return out;
}

std::vector<material::Mat3d> TissueFieldEvaluator::deformation_gradients(Vec y) const {
  const ReadArray state(y);
  const int points = static_cast<int>(shape_values_.size());
  std::vector<material::Mat3d> F(point_positions_.size(), material::Mat3d::identity());
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < system_.dof_map().tissue_tets.size(); ++k) {
    std::array<double, elements::kMaxElementDofs> u_e;
    system_.gather(k, state.data(), u_e.data());
    for (int q = 0; q < points; ++q) elements::add_field_gradient(system_.geometry(k), q, u_e.data(), F[k * points + q]);
  }
  return F;
}

}  // namespace needlefem::fields
