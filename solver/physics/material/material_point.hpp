// Material-point driver: homogeneous deformation histories without a mesh, for checking
// material parameters (`needlefem material-test`) and as a reference in tests.
//
// Axial histories (uniaxial, relaxation, constant-rate) load along e1 with traction-free
// lateral faces:
//  * laws with an isochoric/volumetric split are driven EXACTLY incompressible:
//    F = diag(λ, λ^-½, λ^-½), σ = F S_iso Fᵀ - p I with p fixed by σ22 = σ33 = 0, so
//    σ11 = (F S_iso Fᵀ)11 - (F S_iso Fᵀ)22 (the bulk modulus K plays no part);
//  * compressible laws (co-rotational linear) solve P22 = P33 = 0 for the lateral stretch.
// Nominal stress = P11 (force per undeformed area), Cauchy stress = σ11.
// Simple shear: F = I + γ e1⊗e2 (J = 1); shear stress σ12 = P12, out-of-plane face σ33 = 0.
#pragma once

#include <vector>

#include "physics/material/material.hpp"

namespace needlefem::material {

enum class LoadHistory {
  Uniaxial,      // stretch 1 -> target in `steps` elastic steps (instantaneous or long-term)
  Shear,         // shear amount 0 -> target in `steps` elastic steps (instantaneous or long-term)
  Relaxation,    // stretch ramped linearly to target in ramp_s, then held for hold_s
  ConstantRate,  // stretch changed at engineering strain rate rate_per_s until it reaches target
};

struct LoadProgram {
  LoadHistory history = LoadHistory::Uniaxial;
  double target = 1.5;      // final stretch, or final shear amount for Shear
  int steps = 20;           // steps of the loading part
  double ramp_s = 0.1;      // Relaxation
  double hold_s = 100.0;    // Relaxation
  double rate_per_s = 1.0;  // ConstantRate
  bool long_term = false;   // Uniaxial/Shear: fully relaxed response instead of the instantaneous one
};

struct MaterialPointRow {
  double time_s = 0.0;
  double stretch = 1.0;
  double shear = 0.0;
  double nominal_stress_pa = 0.0;  // axial P11, or shear P12
  double cauchy_stress_pa = 0.0;   // axial σ11, or shear σ12
  double log_strain = 0.0;         // axial: ln λ; shear: max principal asinh(γ/2)
  double strain_rate_per_s = 0.0;  // axial: λ̇/λ; shear: max principal of D; inf = instantaneous
};

struct AxialResponse {
  double cauchy_stress = 0.0, nominal_stress = 0.0, lateral_stretch = 1.0;
  ViscousState state;
};
// Uniaxial state at stretch λ after a step of dt from `old` (lateral faces traction-free).
AxialResponse uniaxial_response(const Material& material, double stretch, const ViscousState& old, double dt);

struct ShearResponse {
  double cauchy_stress = 0.0, nominal_stress = 0.0;
  ViscousState state;
};
ShearResponse simple_shear_response(const Material& material, double shear, const ViscousState& old, double dt);

// The rows of a history, starting with the undeformed state at t = 0. Relaxation rows: every
// ramp step, then the times m·10^k (m = 1..9) inside the hold, and its end.
std::vector<MaterialPointRow> run_material_point(const Material& material, const LoadProgram& program);

}  // namespace needlefem::material
