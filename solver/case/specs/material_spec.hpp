// The tissue material a case describes ([material] keys), parsed and checked: the input of
// material::material_from_spec (physics/material/material.hpp).
#pragma once

#include <string>
#include <vector>

namespace needlefem {

class Case;

enum class MaterialModel { polynomial, corotational_linear };
enum class MaterialPreset { miller_brain, miller_brain_c10_c20, custom };

// Instantaneous polynomial coefficients (Pa) of material.preset = "custom"; a key not given is 0.
struct PolynomialCoefficientsPa {
  double c10, c01, c20, c11, c02;
};

struct PronyTermSpec {
  double g;      // relative modulus (material.prony_g)
  double tau_s;  // relaxation time (material.prony_tau_s)
};

struct MaterialSpec {
  MaterialModel model;
  // Polynomial model: the preset, the bulk modulus, and (preset custom only) the coefficients and
  // Prony series the case enters.
  MaterialPreset preset;
  double bulk_modulus_pa;
  PolynomialCoefficientsPa custom_coefficients;
  std::vector<PronyTermSpec> custom_prony;  // empty: elastic
  // Corotational-linear model.
  double youngs_modulus_pa;
  double poisson_ratio;
};

// material.preset's name for `preset` ("miller-brain", ...), the name outputs give the material.
const std::string& material_preset_name(MaterialPreset preset);

// The case's [material] table. Throws CaseError naming the key for inconsistent input: a
// coefficient or Prony key given with a named preset or another model, material.preset given with
// the corotational-linear model, a Poisson ratio of 0.5, a non-positive instantaneous shear
// modulus, a Prony series whose lists differ in length or whose moduli sum to 1 or more.
MaterialSpec parse_material_spec(const Case& c);

}  // namespace needlefem
