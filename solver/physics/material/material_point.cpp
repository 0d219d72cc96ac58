#include "physics/material/material_point.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

namespace needlefem::material {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Lateral stretch s of a compressible law in uniaxial tension: Newton on P22(diag(λ, s, s)) = 0,
// with dP22/ds = A_2222 + A_2233 from the consistent tangent.
double traction_free_lateral_stretch(const Material& material, double stretch, const ViscousState& old, double dt) {
  double lateral = 1.0;
  const double tolerance = 1e-13 * material.instantaneous_shear_modulus();
  for (int iteration = 0; iteration < 50; ++iteration) {
    const Mat3d F = Mat3d::diagonal(stretch, lateral, lateral);
    const double residual = material.update(F, old, dt).first_pk(1, 1);
    if (std::abs(residual) <= tolerance) return lateral;
    const Tensor4 A = material.tangent(F, old, dt);
    lateral -= residual / (A(1, 1, 1, 1) + A(1, 1, 2, 2));
    if (!(lateral > 0.0)) break;
  }
  throw std::runtime_error(
      fmt::format("material-point driver: no traction-free lateral stretch found at stretch {}", stretch));
}

// Isochoric stress of a split law mapped to the current configuration: F S_iso Fᵀ (J = 1).
Mat3d push_forward_isochoric(const Material& material, const Mat3d& F, const ViscousState& old, double dt) {
  return F * material.isochoric_second_pk(F, old, dt) * transpose(F);
}

}  // namespace

AxialResponse uniaxial_response(const Material& material, double stretch, const ViscousState& old, double dt) {
  AxialResponse response;
  if (material.incompressible()) {
    response.lateral_stretch = 1.0 / std::sqrt(stretch);
    const Mat3d F = Mat3d::diagonal(stretch, response.lateral_stretch, response.lateral_stretch);
    const Mat3d tau = push_forward_isochoric(material, F, old, dt);
    response.cauchy_stress = tau(0, 0) - tau(1, 1);  // the pressure makes σ22 = 0
    response.nominal_stress = response.cauchy_stress / stretch;
    response.state = material.advance(F, old, dt);
    return response;
  }
  response.lateral_stretch = traction_free_lateral_stretch(material, stretch, old, dt);
  const double s = response.lateral_stretch;
  const MaterialPointResult point = material.update(Mat3d::diagonal(stretch, s, s), old, dt);
  response.nominal_stress = point.first_pk(0, 0);
  response.cauchy_stress = point.first_pk(0, 0) / (s * s);  // σ = P Fᵀ / J
  response.state = point.state;
  return response;
}

ShearResponse simple_shear_response(const Material& material, double shear, const ViscousState& old, double dt) {
  Mat3d F = Mat3d::identity();
  F(0, 1) = shear;
  ShearResponse response;
  Mat3d cauchy;
  if (material.incompressible()) {
    const Mat3d tau = push_forward_isochoric(material, F, old, dt);
    cauchy = tau - tau(2, 2) * Mat3d::identity();  // the pressure makes σ33 = 0
    response.state = material.advance(F, old, dt);
  } else {
    const MaterialPointResult point = material.update(F, old, dt);
    cauchy = point.first_pk * transpose(F);  // J = 1
    response.state = point.state;
  }
  response.cauchy_stress = cauchy(0, 1);
  response.nominal_stress = (cauchy * transpose(inverse(F)))(0, 1);
  return response;
}

std::vector<MaterialPointRow> run_material_point(const Material& material, const LoadProgram& program) {
  if (program.steps < 1) throw std::invalid_argument("material-test: --steps must be at least 1");
  const bool shear_history = program.history == LoadHistory::Shear;
  if (!shear_history && !(program.target > 0.0))
    throw std::invalid_argument(fmt::format("material-test: --to {} is not a positive stretch", program.target));

  std::vector<MaterialPointRow> rows;
  ViscousState state = material.initial_state();
  auto axial_row = [&](double time, double stretch, double stretch_rate, double dt) {
    const AxialResponse response = uniaxial_response(material, stretch, state, dt);
    state = response.state;
    rows.push_back({time, stretch, 0.0, response.nominal_stress, response.cauchy_stress, std::log(stretch),
                    stretch_rate / stretch});
  };
  // Time-resolved loading: a linear stretch ramp from 1 over `duration`, in `steps` steps.
  auto ramp = [&](double duration) {
    const double stretch_rate = (program.target - 1.0) / duration;
    rows.push_back({0.0, 1.0, 0.0, 0.0, 0.0, 0.0, stretch_rate});
    for (int k = 1; k <= program.steps; ++k) {
      const double time = duration * k / program.steps;
      axial_row(time, 1.0 + stretch_rate * time, stretch_rate, duration / program.steps);
    }
  };

  switch (program.history) {
    case LoadHistory::Uniaxial:
    case LoadHistory::Shear: {
      // Elastic limits of the viscoelastic law: dt = 0 (instantaneous) or +inf (relaxed).
      const double dt = program.long_term ? kInfinity : 0.0;
      const double rate = program.long_term ? 0.0 : kInfinity;
      for (int k = 0; k <= program.steps; ++k) {
        const double fraction = static_cast<double>(k) / program.steps;
        if (shear_history) {
          const double shear = program.target * fraction;
          const ShearResponse response = simple_shear_response(material, shear, state, dt);
          state = response.state;
          rows.push_back({0.0, 1.0, shear, response.nominal_stress, response.cauchy_stress, std::asinh(0.5 * shear),
                          k == 0 ? 0.0 : rate});
        } else {
          axial_row(0.0, 1.0 + (program.target - 1.0) * fraction, k == 0 ? 0.0 : rate, dt);
        }
      }
      break;
    }
    case LoadHistory::Relaxation: {
      if (!(program.ramp_s > 0.0) || !(program.hold_s >= 0.0))
        throw std::invalid_argument("material-test: --ramp must be positive and --hold non-negative");
      ramp(program.ramp_s);
      const double end = program.ramp_s + program.hold_s;
      std::vector<double> hold_times;
      for (int decade = static_cast<int>(std::floor(std::log10(program.ramp_s)));
           decade <= static_cast<int>(std::ceil(std::log10(std::max(end, program.ramp_s)))); ++decade)
        for (int m = 1; m <= 9; ++m) {
          const double time = m * std::pow(10.0, decade);
          if (time > program.ramp_s * (1.0 + 1e-9) && time < end * (1.0 - 1e-12)) hold_times.push_back(time);
        }
      if (program.hold_s > 0.0) hold_times.push_back(end);
      double previous = program.ramp_s;
      for (double time : hold_times) {
        axial_row(time, program.target, 0.0, time - previous);
        previous = time;
      }
      break;
    }
    case LoadHistory::ConstantRate: {
      if (!(program.rate_per_s > 0.0)) throw std::invalid_argument("material-test: --rate must be positive");
      if (program.target == 1.0) throw std::invalid_argument("material-test: --to must differ from 1");
      ramp(std::abs(program.target - 1.0) / program.rate_per_s);
      break;
    }
  }
  return rows;
}

}  // namespace needlefem::material
