// Material dispatch, presets and construction from a case's [material] table (MaterialSpec).
//
// Presets (paper 001 and Miller 1999, "Constitutive model of brain tissue suitable for finite
// element analysis of surgical procedures", J. Biomech. 32:531), instantaneous moduli:
//   miller-brain          C10 = C01 = 263 Pa, C20 = C02 = 491 Pa (mu0 = 1052 Pa)
//   miller-brain-c10-c20  C10 = 263 Pa, C20 = 491 Pa (paper 001's literal print, mu0 = 526 Pa)
// both with Prony g1 = 0.450, tau1 = 0.5 s; g2 = 0.365, tau2 = 50 s (g∞ = 0.185).
#include "physics/material/material.hpp"

#include <stdexcept>
#include <type_traits>

#include <fmt/format.h>

#include "case/case.hpp"

namespace needlefem::material {

namespace {

const std::vector<PronyTerm> kMillerProny{{0.450, 0.5}, {0.365, 50.0}};

PolynomialIsochoric preset_coefficients(MaterialPreset preset) {
  if (preset == MaterialPreset::miller_brain)
    return {.c10 = 263.0, .c01 = 263.0, .c20 = 491.0, .c11 = 0.0, .c02 = 491.0};
  return {.c10 = 263.0, .c01 = 0.0, .c20 = 491.0, .c11 = 0.0, .c02 = 0.0};  // miller-brain-c10-c20
}

}  // namespace

ViscousState Material::initial_state() const {
  return std::visit([](const auto& law) { return law.initial_state(); }, law_);
}

const std::vector<PronyTerm>& Material::prony() const {
  return std::visit([](const auto& law) -> const std::vector<PronyTerm>& { return law.prony(); }, law_);
}

template <class T>
Mat3<T> Material::stepped_second_pk(const Mat3<T>& F, const ViscousState& old, double dt) const {
  return std::visit([&](const auto& law) { return law.second_pk(F, old, dt); }, law_);
}

MaterialPointResult Material::update(const Mat3d& F, const ViscousState& old, double dt) const {
  const Mat3d S = stepped_second_pk(F, old, dt);
  return {F * S, S, advance(F, old, dt)};
}

Mat3d Material::isochoric_second_pk(const Mat3d& F, const ViscousState& old, double dt) const {
  return std::visit(
      [&](const auto& law) -> Mat3d {
        if constexpr (std::decay_t<decltype(law)>::kVolumetricSplit)
          return law.isochoric_second_pk(F, old, dt);
        else
          throw std::invalid_argument("material '" + name_ + "' has no isochoric/volumetric split");
      },
      law_);
}

ViscousState Material::advance(const Mat3d& F, const ViscousState& old, double dt) const {
  return std::visit([&](const auto& law) { return law.advance(F, old, dt); }, law_);
}

Tensor4 Material::tangent(const Mat3d& F, const ViscousState& old, double dt) const {
  return directional_jacobian(F, false, [&](const Mat3<Dual>& f) { return f * stepped_second_pk(f, old, dt); });
}

Tensor4 Material::tangent_green_strain(const Mat3d& F, const ViscousState& old, double dt) const {
  return green_strain_tangent(F, [&](const Mat3<Dual>& f) { return stepped_second_pk(f, old, dt); });
}

double Material::instantaneous_energy(const Mat3d& F) const {
  return std::visit([&](const auto& law) { return law.energy(F); }, law_);
}

double Material::instantaneous_shear_modulus() const {
  return std::visit([](const auto& law) { return law.instantaneous_shear_modulus(); }, law_);
}

double Material::long_term_shear_modulus() const {
  return std::visit([](const auto& law) { return law.long_term_shear_modulus(); }, law_);
}

std::string Material::description() const {
  return name_ + ": " + std::visit([](const auto& law) { return law.description(); }, law_);
}

const std::vector<std::string>& material_preset_names() {
  static const std::vector<std::string> names{"miller-brain", "miller-brain-c10-c20"};
  return names;
}

Material material_preset(const std::string& name) {
  if (name == "custom") throw CaseError("--material: 'custom' needs a case file with a [material] table (--case)");
  const Case preset = Case::parse(fmt::format("[material]\npreset = \"{}\"\n", name), "--material");
  return material_from_spec(parse_material_spec(preset));
}

Material material_from_spec(const MaterialSpec& spec) {
  if (spec.model == MaterialModel::corotational_linear)
    return Material("corotational-linear",
                    CorotationalLinear{.youngs_modulus = spec.youngs_modulus_pa, .poisson_ratio = spec.poisson_ratio});
  PolynomialTissue tissue;
  tissue.volumetric.bulk_modulus = spec.bulk_modulus_pa;
  if (spec.preset == MaterialPreset::custom) {
    const PolynomialCoefficientsPa& c = spec.custom_coefficients;
    tissue.isochoric.elastic = {.c10 = c.c10, .c01 = c.c01, .c20 = c.c20, .c11 = c.c11, .c02 = c.c02};
    for (const PronyTermSpec& term : spec.custom_prony) tissue.isochoric.terms.push_back({term.g, term.tau_s});
  } else {
    tissue.isochoric.elastic = preset_coefficients(spec.preset);
    tissue.isochoric.terms = kMillerProny;
  }
  return Material(material_preset_name(spec.preset), tissue);
}

}  // namespace needlefem::material
