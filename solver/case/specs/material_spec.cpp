#include "case/specs/material_spec.hpp"

#include <array>
#include <numeric>
#include <utility>

#include <fmt/format.h>

#include "case/case.hpp"
#include "case/specs/choice.hpp"

namespace needlefem {

namespace {

const std::array<std::pair<std::string, MaterialPreset>, 3> kPresetNames{{
    {"miller-brain", MaterialPreset::miller_brain},
    {"miller-brain-c10-c20", MaterialPreset::miller_brain_c10_c20},
    {"custom", MaterialPreset::custom},
}};

const std::array kModels{std::pair{"polynomial", MaterialModel::polynomial},
                         std::pair{"corotational-linear", MaterialModel::corotational_linear}};

const std::vector<std::string> kCoefficientKeys{"material.c10_instantaneous_pa", "material.c01_instantaneous_pa",
                                                "material.c20_instantaneous_pa", "material.c11_instantaneous_pa",
                                                "material.c02_instantaneous_pa"};

// The coefficient and Prony keys apply to the polynomial model's custom preset only.
void require_no_custom_keys(const Case& c) {
  const std::string preset = c.text("material.preset");
  const bool polynomial = c.text("material.model") == "polynomial";
  std::vector<std::string> custom_keys = kCoefficientKeys;
  custom_keys.insert(custom_keys.end(), {"material.prony_g", "material.prony_tau_s"});
  for (const auto& key : custom_keys)
    if (c.given(key))
      throw c.error(key, !polynomial ? "applies to material.model = \"polynomial\" only"
                                     : fmt::format("given with material.preset = \"{}\", which fixes the "
                                                   "instantaneous coefficients and Prony series; set "
                                                   "material.preset = \"custom\" to enter your own",
                                                   preset));
}

PolynomialCoefficientsPa custom_coefficients(const Case& c) {
  std::vector<double> v;
  for (const auto& key : kCoefficientKeys) v.push_back(c.maybe_real(key).value_or(0.0));
  const PolynomialCoefficientsPa coefficients{.c10 = v[0], .c01 = v[1], .c20 = v[2], .c11 = v[3], .c02 = v[4]};
  if (!(2.0 * (coefficients.c10 + coefficients.c01) > 0.0))
    throw c.error("material.c10_instantaneous_pa", "the instantaneous shear modulus 2 (C10 + C01) must be positive");
  return coefficients;
}

std::vector<PronyTermSpec> custom_prony(const Case& c) {
  const bool has_g = c.has("material.prony_g"), has_tau = c.has("material.prony_tau_s");
  if (has_g != has_tau)
    throw c.error(has_g ? "material.prony_tau_s" : "material.prony_g",
                  "prony_g and prony_tau_s must be given together");
  if (!has_g) return {};
  const auto g = c.reals("material.prony_g"), tau = c.reals("material.prony_tau_s");
  if (g.size() != tau.size())
    throw c.error("material.prony_tau_s",
                  fmt::format("has {} entries but material.prony_g has {}", tau.size(), g.size()));
  if (std::accumulate(g.begin(), g.end(), 0.0) >= 1.0)
    throw c.error("material.prony_g", "the relative moduli must sum to less than 1 (g∞ > 0)");
  std::vector<PronyTermSpec> terms;
  for (std::size_t i = 0; i < g.size(); ++i) terms.push_back({g[i], tau[i]});
  return terms;
}

}  // namespace

const std::string& material_preset_name(MaterialPreset preset) { return choice_name(kPresetNames, preset); }

MaterialSpec parse_material_spec(const Case& c) {
  MaterialSpec spec{};
  spec.model = parse_choice(c, "material.model", kModels);
  spec.preset = parse_choice(c, "material.preset", kPresetNames);
  if (spec.preset != MaterialPreset::custom || spec.model != MaterialModel::polynomial) require_no_custom_keys(c);
  spec.youngs_modulus_pa = c.real("material.youngs_modulus_pa");
  spec.poisson_ratio = c.real("material.poisson_ratio");
  spec.bulk_modulus_pa = c.real("material.bulk_modulus_pa");
  if (spec.model == MaterialModel::corotational_linear) {
    if (c.given("material.preset")) throw c.error("material.preset", "applies to material.model = \"polynomial\" only");
    if (!(spec.poisson_ratio < 0.5))
      throw c.error("material.poisson_ratio", "must be below 0.5 (linear elasticity has no incompressible limit)");
    return spec;
  }
  if (spec.preset == MaterialPreset::custom) {
    spec.custom_coefficients = custom_coefficients(c);
    spec.custom_prony = custom_prony(c);
  }
  return spec;
}

}  // namespace needlefem
