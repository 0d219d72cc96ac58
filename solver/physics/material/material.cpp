// Material dispatch, presets and construction from a case's [material] table.
//
// Presets (paper 001 and Miller 1999, "Constitutive model of brain tissue suitable for finite
// element analysis of surgical procedures", J. Biomech. 32:531), instantaneous moduli:
//   miller-brain          C10 = C01 = 263 Pa, C20 = C02 = 491 Pa (mu0 = 1052 Pa)
//   miller-brain-c10-c20  C10 = 263 Pa, C20 = 491 Pa (paper 001's literal print, mu0 = 526 Pa)
// both with Prony g1 = 0.450, tau1 = 0.5 s; g2 = 0.365, tau2 = 50 s (g∞ = 0.185).
#include "physics/material/material.hpp"

#include <numeric>
#include <stdexcept>
#include <type_traits>

#include <fmt/format.h>

#include "case/case.hpp"

namespace needlefem::material {

namespace {

const std::vector<PronyTerm> kMillerProny{{0.450, 0.5}, {0.365, 50.0}};

const std::vector<std::string> kCoefficientKeys{"material.c10_instantaneous_pa", "material.c01_instantaneous_pa",
                                                "material.c20_instantaneous_pa", "material.c11_instantaneous_pa",
                                                "material.c02_instantaneous_pa"};

PolynomialIsochoric preset_coefficients(const std::string& preset) {
  if (preset == "miller-brain") return {.c10 = 263.0, .c01 = 263.0, .c20 = 491.0, .c11 = 0.0, .c02 = 491.0};
  return {.c10 = 263.0, .c01 = 0.0, .c20 = 491.0, .c11 = 0.0, .c02 = 0.0};  // miller-brain-c10-c20
}

PolynomialIsochoric custom_coefficients(const Case& input) {
  std::vector<double> c;
  for (const auto& key : kCoefficientKeys) c.push_back(input.maybe_real(key).value_or(0.0));
  PolynomialIsochoric law{.c10 = c[0], .c01 = c[1], .c20 = c[2], .c11 = c[3], .c02 = c[4]};
  if (!(law.initial_shear_modulus() > 0.0))
    throw input.error("material.c10_instantaneous_pa",
                      "the instantaneous shear modulus 2 (C10 + C01) must be positive");
  return law;
}

std::vector<PronyTerm> custom_prony(const Case& input) {
  const bool has_g = input.has("material.prony_g"), has_tau = input.has("material.prony_tau_s");
  if (has_g != has_tau)
    throw input.error(has_g ? "material.prony_tau_s" : "material.prony_g",
                      "prony_g and prony_tau_s must be given together");
  if (!has_g) return {};
  const auto g = input.reals("material.prony_g"), tau = input.reals("material.prony_tau_s");
  if (g.size() != tau.size())
    throw input.error("material.prony_tau_s",
                      fmt::format("has {} entries but material.prony_g has {}", tau.size(), g.size()));
  if (std::accumulate(g.begin(), g.end(), 0.0) >= 1.0)
    throw input.error("material.prony_g", "the relative moduli must sum to less than 1 (g∞ > 0)");
  std::vector<PronyTerm> terms;
  for (std::size_t i = 0; i < g.size(); ++i) terms.push_back({g[i], tau[i]});
  return terms;
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
  return material_from_case(Case::parse(fmt::format("[material]\npreset = \"{}\"\n", name), "--material"));
}

Material material_from_case(const Case& input) {
  const std::string preset = input.text("material.preset");
  const std::string model = input.text("material.model");

  std::vector<std::string> custom_keys = kCoefficientKeys;
  custom_keys.insert(custom_keys.end(), {"material.prony_g", "material.prony_tau_s"});
  if (preset != "custom" || model != "polynomial")
    for (const auto& key : custom_keys)
      if (input.given(key))
        throw input.error(key, model != "polynomial"
                                   ? "applies to material.model = \"polynomial\" only"
                                   : fmt::format("given with material.preset = \"{}\", which fixes the "
                                                 "instantaneous coefficients and Prony series; set "
                                                 "material.preset = \"custom\" to enter your own",
                                                 preset));

  if (model == "corotational-linear") {
    if (input.given("material.preset"))
      throw input.error("material.preset", "applies to material.model = \"polynomial\" only");
    const double nu = input.real("material.poisson_ratio");
    if (!(nu < 0.5))
      throw input.error("material.poisson_ratio", "must be below 0.5 (linear elasticity has no incompressible limit)");
    return Material("corotational-linear",
                    CorotationalLinear{.youngs_modulus = input.real("material.youngs_modulus_pa"), .poisson_ratio = nu});
  }

  PolynomialTissue tissue;
  tissue.volumetric.bulk_modulus = input.real("material.bulk_modulus_pa");
  if (preset == "custom") {
    tissue.isochoric.elastic = custom_coefficients(input);
    tissue.isochoric.terms = custom_prony(input);
  } else {
    tissue.isochoric.elastic = preset_coefficients(preset);
    tissue.isochoric.terms = kMillerProny;
  }
  return Material(preset, tissue);
}

}  // namespace needlefem::material
