// Equations and sources: tet_element.hpp.
#include "physics/elements/tet_element.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace needlefem::elements {

namespace {

using material::Mat3d;
using material::to_voigt;

Mat3d to_mat3(const std::array<double, 9>& a) {
  Mat3d m;
  m.a = a;
  return m;
}

// Pass 1: F at every point into result.points and v_e = Σ_q w_q J_q (the mixed form needs v_e
// before any stress). False, with result.inverted set, if det F <= 0 at some point.
bool deformation_gradients(const ElementGeometry& geometry, const double* displacement, ElementResult& result,
                           double& current_volume) {
  current_volume = 0.0;
  for (int q = 0; q < geometry.points; ++q) {
    Mat3d F = Mat3d::identity();
    add_field_gradient(geometry, q, displacement, F);
    const double det_f = material::det(F);
    if (!(det_f > 0.0)) {
      result.inverted = true;
      return false;
    }
    result.points[q].deformation_gradient = F.a;
    current_volume += geometry.weight[q] * det_f;
  }
  return true;
}

// Buffers of one element's tangent (sized for with_tangent only).
struct TangentScratch {
  std::vector<double> B, DB;  // B_q and D B_q, 6 x 3n
  explicit TangentScratch(int dofs) : B(kVoigt * dofs), DB(kVoigt * dofs) {}
};

// K += scale B_qᵀ D B_q (the material part at point q).
void add_material_stiffness(const PointResult& point, const double* G, int n, double scale, TangentScratch& scratch,
                            std::vector<double>& K) {
  const int dofs = 3 * n;
  std::vector<double>& B = scratch.B;
  std::vector<double>& DB = scratch.DB;
  green_strain_operator(point.deformation_gradient, G, n, B.data());
  for (int m = 0; m < kVoigt; ++m)
    for (int c = 0; c < dofs; ++c) {
      double s = 0.0;
      for (int l = 0; l < kVoigt; ++l) s += point.elastic_tangent[m * kVoigt + l] * B[static_cast<std::size_t>(l) * dofs + c];
      DB[static_cast<std::size_t>(m) * dofs + c] = s;
    }
  for (int row = 0; row < dofs; ++row)
    for (int col = 0; col < dofs; ++col) {
      double s = 0.0;
      for (int m = 0; m < kVoigt; ++m)
        s += B[static_cast<std::size_t>(m) * dofs + row] * DB[static_cast<std::size_t>(m) * dofs + col];
      K[static_cast<std::size_t>(row) * dofs + col] += scale * s;
    }
}

// Geometric stiffness K += w δ_ik G_a·S G_b.
void add_geometric_stiffness(const Mat3d& stress, const double* G, int n, double w, std::vector<double>& K) {
  const int dofs = 3 * n;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      double s = 0.0;
      for (int I = 0; I < 3; ++I)
        for (int J = 0; J < 3; ++J) s += G[3 * a + I] * stress(I, J) * G[3 * b + J];
      for (int i = 0; i < 3; ++i) K[static_cast<std::size_t>(3 * a + i) * dofs + 3 * b + i] += w * s;
    }
}

// n_ai = ∂N_a/∂x_i = G_aJ F⁻¹_Ji.
void spatial_gradients(const Mat3d& F, const double* G, int n, double* spatial_gradient) {
  const Mat3d f_inverse = material::inverse(F);
  for (int a = 0; a < n; ++a)
    for (int i = 0; i < 3; ++i) {
      double s = 0.0;
      for (int J = 0; J < 3; ++J) s += G[3 * a + J] * f_inverse(J, i);
      spatial_gradient[3 * a + i] = s;
    }
}

// Adds c (n_ai n_bk - n_ak n_bi), the J-normalised second derivative of J, to `target`.
void add_jacobian_hessian(const double* spatial_gradient, int n, double c, std::vector<double>& target) {
  const int dofs = 3 * n;
  for (int a = 0; a < n; ++a)
    for (int i = 0; i < 3; ++i)
      for (int b = 0; b < n; ++b)
        for (int k = 0; k < 3; ++k)
          target[static_cast<std::size_t>(3 * a + i) * dofs + 3 * b + k] +=
              c * (spatial_gradient[3 * a + i] * spatial_gradient[3 * b + k] -
                   spatial_gradient[3 * a + k] * spatial_gradient[3 * b + i]);
}

// The mixed element's volumetric part from U at θ = v_e/V_e: p ∂v_e/∂u in the residual and
// p ∂²v_e/∂u² + U''(θ)/V_e (∂v_e/∂u)(∂v_e/∂u)ᵀ in the tangent, p the given pressure or U'(θ).
void add_mean_dilatation(const material::VolumetricResponse& at_theta, const ElementGeometry& geometry,
                         const std::vector<double>& volume_hessian, const double* given_pressure, bool with_tangent,
                         ElementResult& result) {
  const int dofs = 3 * geometry.nodes;
  const auto& volume_gradient = result.volume_gradient;
  result.volume_pressure = at_theta.pressure;
  result.pressure_stiffness = at_theta.slope / geometry.volume;
  const double p = given_pressure ? *given_pressure : result.volume_pressure;
  result.pressure = p;
  result.energy += geometry.volume * at_theta.energy;
  for (int c = 0; c < dofs; ++c) result.residual[c] += p * volume_gradient[c];
  if (!with_tangent) return;
  const double stiffness_per_volume = at_theta.slope / geometry.volume;
  for (int row = 0; row < dofs; ++row)
    for (int col = 0; col < dofs; ++col)
      result.stiffness[static_cast<std::size_t>(row) * dofs + col] +=
          p * volume_hessian[static_cast<std::size_t>(row) * dofs + col] +
          stiffness_per_volume * volume_gradient[row] * volume_gradient[col];
}

}  // namespace

const std::vector<QuadraturePoint>& element_quadrature(int nodes_per_tet) {
  // Keast's 4-point rule: points at (a, b, b) and permutations, a = (5 + 3√5)/20, b = (5 - √5)/20.
  static const std::vector<QuadraturePoint> four_point = [] {
    const double a = (5.0 + 3.0 * std::sqrt(5.0)) / 20.0, b = (5.0 - std::sqrt(5.0)) / 20.0;
    return std::vector<QuadraturePoint>{
        {{b, b, b}, 1.0 / 24.0}, {{a, b, b}, 1.0 / 24.0}, {{b, a, b}, 1.0 / 24.0}, {{b, b, a}, 1.0 / 24.0}};
  }();
  static const std::vector<QuadraturePoint> centroid{{{0.25, 0.25, 0.25}, 1.0 / 6.0}};
  if (nodes_per_tet == 10) return four_point;
  if (nodes_per_tet == 4) return centroid;
  throw std::invalid_argument("element_quadrature: tetrahedra have 4 or 10 nodes");
}

ElementGeometry element_geometry(int nodes_per_tet, const double* coordinates) {
  const auto& rule = element_quadrature(nodes_per_tet);
  ElementGeometry g;
  g.nodes = nodes_per_tet;
  g.points = static_cast<int>(rule.size());
  g.gradient.resize(static_cast<std::size_t>(g.points) * g.nodes * 3);
  g.weight.resize(g.points);
  std::vector<double> reference_gradient(static_cast<std::size_t>(g.nodes) * 3);
  for (int q = 0; q < g.points; ++q) {
    tet_shape_gradients(g.nodes, rule[q].xi, reference_gradient.data());
    Mat3d jacobian;  // ∂X_i/∂ξ_j
    for (int a = 0; a < g.nodes; ++a)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) jacobian(i, j) += coordinates[3 * a + i] * reference_gradient[3 * a + j];
    const double det_jacobian = material::det(jacobian);
    if (!(det_jacobian > 0.0)) throw std::runtime_error("element_geometry: inverted or degenerate reference element");
    const Mat3d inverse_jacobian = material::inverse(jacobian);  // ∂ξ_j/∂X_J
    double* G = g.gradient.data() + static_cast<std::size_t>(q) * g.nodes * 3;
    for (int a = 0; a < g.nodes; ++a)
      for (int J = 0; J < 3; ++J) {
        double s = 0.0;
        for (int j = 0; j < 3; ++j) s += reference_gradient[3 * a + j] * inverse_jacobian(j, J);
        G[3 * a + J] = s;
      }
    g.weight[q] = rule[q].weight * det_jacobian;
    g.volume += g.weight[q];
  }
  return g;
}

void add_field_gradient(const ElementGeometry& geometry, int q, const double* values, Mat3d& sum) {
  const double* G = geometry.gradient_at(q);
  for (int a = 0; a < geometry.nodes; ++a)
    for (int i = 0; i < 3; ++i)
      for (int J = 0; J < 3; ++J) sum(i, J) += values[3 * a + i] * G[3 * a + J];
}

void green_strain_operator(const std::array<double, 9>& F, const double* gradient, int nodes, double* B) {
  const int columns = 3 * nodes;
  for (int a = 0; a < nodes; ++a) {
    const double* G = gradient + 3 * a;
    for (int i = 0; i < 3; ++i) {
      const double* f = F.data() + 3 * i;  // row i of F: F_iI
      const int c = 3 * a + i;
      B[0 * columns + c] = f[0] * G[0];
      B[1 * columns + c] = f[1] * G[1];
      B[2 * columns + c] = f[2] * G[2];
      B[3 * columns + c] = f[1] * G[2] + f[2] * G[1];
      B[4 * columns + c] = f[0] * G[2] + f[2] * G[0];
      B[5 * columns + c] = f[0] * G[1] + f[1] * G[0];
    }
  }
}

TetElementKernel::TetElementKernel(const material::Material& material, Formulation formulation)
    : material_(material), formulation_(formulation) {
  if (formulation == Formulation::mean_dilatation && !material.incompressible())
    throw std::invalid_argument("the mean-dilatation element needs a law with an isochoric/volumetric split; '" +
                                material.name() + "' has none (use the displacement formulation)");
}

ElementResult TetElementKernel::evaluate(const ElementGeometry& geometry, const double* displacement,
                                         const ViscousStep* viscous, bool with_tangent,
                                         const double* given_pressure) const {
  if (3 * geometry.nodes > kMaxElementDofs || geometry.points > kMaxElementPoints)
    throw std::invalid_argument("element evaluation: more nodes or quadrature points than a TET10's");
  return std::visit(
      [&](const auto& law) {
        return evaluate_law(law, geometry, displacement, viscous, with_tangent, given_pressure);
      },
      material_.law());
}

template <class Law>
ElementResult TetElementKernel::evaluate_law(const Law& law, const ElementGeometry& geometry,
                                             const double* displacement, const ViscousStep* viscous,
                                             bool with_tangent, const double* given_pressure) const {
  const int n = geometry.nodes, dofs = 3 * n;
  const bool viscoelastic = viscous && !law.prony().empty();
  const std::size_t values_per_point = material::prony_history_size(law.prony().size());
  const double material_tangent_scale = viscoelastic ? viscous->step->elastic_fraction : 1.0;
  ElementResult result;
  double current_volume = 0.0;
  if (!deformation_gradients(geometry, displacement, result, current_volume)) return result;

  if (with_tangent) result.stiffness.assign(static_cast<std::size_t>(dofs) * dofs, 0.0);
  double* r = result.residual.data();
  std::vector<double>& K = result.stiffness;
  const bool mixed = formulation_ == Formulation::mean_dilatation;
  TangentScratch scratch(with_tangent ? dofs : 0);
  std::array<double, kMaxElementDofs> spatial_gradient{};  // n_ai = ∂N_a/∂x_i
  std::vector<double> volume_hessian(mixed && with_tangent ? K.size() : 0);  // ∂²v_e/∂u²
  double pressure_volume_integral = 0.0;

  for (int q = 0; q < geometry.points; ++q) {
    const double w = geometry.weight[q];
    const double* G = geometry.gradient_at(q);
    PointResult& point = result.points[q];
    const Mat3d F = to_mat3(point.deformation_gradient);
    material::ViscousStress viscous_stress;
    if (viscoelastic) viscous_stress = material::viscous_stress(*viscous->step, viscous->history + q * values_per_point);
    const material::PointResponse response =
        law.respond(F, viscoelastic ? &viscous_stress : nullptr, with_tangent ? &point.elastic_tangent : nullptr);
    point.stress = to_voigt(response.stress);
    point.elastic_stress = to_voigt(response.elastic_stress);
    result.energy += w * response.energy;
    add_green_strain_transpose(point.deformation_gradient, G, n, point.stress, w, r);
    if (with_tangent) {
      add_material_stiffness(point, G, n, w * material_tangent_scale, scratch, K);
      add_geometric_stiffness(response.stress, G, n, w, K);
    }
    if constexpr (Law::kVolumetricSplit) {
      // Volumetric part: at the point's J (displacement) or through v_e (mixed, below).
      const double det_f = material::det(F);
      const material::VolumetricResponse& volumetric = response.volumetric;
      point.pressure = volumetric.pressure;
      spatial_gradients(F, G, n, spatial_gradient.data());
      if (mixed) {
        for (int c = 0; c < dofs; ++c) result.volume_gradient[c] += w * det_f * spatial_gradient[c];
        if (with_tangent) add_jacobian_hessian(spatial_gradient.data(), n, w * det_f, volume_hessian);
      } else {
        const double p = volumetric.pressure;
        result.energy += w * volumetric.energy;
        pressure_volume_integral += w * p;
        for (int c = 0; c < dofs; ++c) r[c] += w * p * det_f * spatial_gradient[c];
        if (with_tangent) {
          for (int row = 0; row < dofs; ++row)
            for (int col = 0; col < dofs; ++col)
              K[static_cast<std::size_t>(row) * dofs + col] +=
                  w * volumetric.slope * det_f * det_f * spatial_gradient[row] * spatial_gradient[col];
          add_jacobian_hessian(spatial_gradient.data(), n, w * p * det_f, K);
        }
      }
    }
  }
  if constexpr (Law::kVolumetricSplit) {
    if (mixed)
      add_mean_dilatation(law.volumetric_response(current_volume / geometry.volume), geometry, volume_hessian,
                          given_pressure, with_tangent, result);
    else
      result.pressure = pressure_volume_integral / geometry.volume;
  }
  return result;
}

}  // namespace needlefem::elements
