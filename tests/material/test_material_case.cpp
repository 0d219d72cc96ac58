// Building a material from a case's [material] table: presets, custom coefficients, and the
// rules that keep instantaneous constants from being entered by mistake.
#include <gtest/gtest.h>

#include <string>

#include "case/case.hpp"
#include "physics/material/material.hpp"

namespace needlefem::material {
namespace {

Material from_text(const std::string& toml) {
  return material_from_spec(parse_material_spec(Case::parse(toml, "test.toml")));
}

std::string error_of(const std::string& toml) {
  try {
    from_text(toml);
  } catch (const CaseError& e) {
    return e.what();
  }
  return "";
}

TEST(MaterialCase, DefaultIsMillerBrain) {
  const Material material = from_text("");
  EXPECT_EQ(material.name(), "miller-brain");
  const auto& tissue = std::get<PolynomialTissue>(material.law());
  EXPECT_DOUBLE_EQ(tissue.isochoric.elastic.c01, 263.0);
  EXPECT_DOUBLE_EQ(tissue.isochoric.elastic.c02, 491.0);
  ASSERT_EQ(tissue.isochoric.terms.size(), 2u);
  EXPECT_NEAR(tissue.isochoric.long_term_fraction(), 0.185, 1e-15);
}

TEST(MaterialCase, CustomCoefficientsAndProny) {
  const Material material = from_text(
      "[material]\npreset = \"custom\"\nc10_instantaneous_pa = 100.0\nc11_instantaneous_pa = 5.0\n"
      "bulk_modulus_pa = 1e5\nprony_g = [0.5]\nprony_tau_s = [2.0]\n");
  const auto& tissue = std::get<PolynomialTissue>(material.law());
  EXPECT_DOUBLE_EQ(tissue.isochoric.elastic.c10, 100.0);
  EXPECT_DOUBLE_EQ(tissue.isochoric.elastic.c01, 0.0);
  EXPECT_DOUBLE_EQ(tissue.isochoric.elastic.c11, 5.0);
  EXPECT_DOUBLE_EQ(tissue.volumetric.bulk_modulus, 1e5);
  EXPECT_DOUBLE_EQ(material.long_term_shear_modulus(), 100.0);
}

TEST(MaterialCase, CoefficientsWithNamedPresetAreRejected) {
  const std::string message = error_of("[material]\nc10_instantaneous_pa = 100.0\n");
  EXPECT_NE(message.find("test.toml"), std::string::npos) << message;
  EXPECT_NE(message.find("material.c10_instantaneous_pa"), std::string::npos) << message;
  EXPECT_NE(message.find("custom"), std::string::npos) << message;
  EXPECT_NE(error_of("[material]\npreset = \"miller-brain-c10-c20\"\nprony_g = [0.1]\nprony_tau_s = [1.0]\n"), "");
}

TEST(MaterialCase, InconsistentProny) {
  const std::string base = "[material]\npreset = \"custom\"\nc10_instantaneous_pa = 100.0\n";
  EXPECT_NE(error_of(base + "prony_g = [0.3, 0.2]\nprony_tau_s = [1.0]\n").find("prony_tau_s"), std::string::npos);
  EXPECT_NE(error_of(base + "prony_g = [0.6, 0.5]\nprony_tau_s = [1.0, 2.0]\n").find("sum"), std::string::npos);
  EXPECT_NE(error_of(base + "prony_g = [0.3]\n").find("together"), std::string::npos);
  EXPECT_NE(error_of("[material]\npreset = \"custom\"\n").find("shear modulus"), std::string::npos);
}

TEST(MaterialCase, CorotationalLinear) {
  const Material material =
      from_text("[material]\nmodel = \"corotational-linear\"\nyoungs_modulus_pa = 3000.0\npoisson_ratio = 0.4\n");
  const auto& law = std::get<CorotationalLinear>(material.law());
  EXPECT_DOUBLE_EQ(law.youngs_modulus, 3000.0);
  EXPECT_NEAR(material.instantaneous_shear_modulus(), 3000.0 / 2.8, 1e-12);
  EXPECT_NE(error_of("[material]\nmodel = \"corotational-linear\"\npoisson_ratio = 0.5\n").find("poisson_ratio"),
            std::string::npos);
  EXPECT_NE(error_of("[material]\nmodel = \"corotational-linear\"\npreset = \"miller-brain\"\n"), "");
}

}  // namespace
}  // namespace needlefem::material
