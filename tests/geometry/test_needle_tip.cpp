// Needle-tip geometry: closed-form volumes and the validity rules of the scene.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "case/case.hpp"
#include "geometry/needle_motion.hpp"
#include "geometry/needle_tip.hpp"

using namespace needlefem;

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double mm = 1e-3;
BevelTip bevel(double r, double alpha_deg, double tau, double shaft = 0.1) {
  return BevelTip{r * mm, alpha_deg * kPi / 180, tau * mm, shaft * mm};
}
std::vector<std::string> rules_of(const std::string& overrides_toml) {
  const Case c = Case::parse(overrides_toml, "rules.toml");
  std::vector<std::string> rules;
  const NeedleTip tip = needle_tip_from_spec(parse_needle_tip_spec(c));
  for (const auto& v : brain_tip_scene_violations(parse_tissue_cube_spec(c), tip)) rules.push_back(v.rule);
  return rules;
}
}  // namespace

TEST(NeedleTip, SharpBevelVolumeMatchesClosedForm) {
  // Cylinder cut by a plane through the full diameter: half of the cylinder of height 2r/tan(alpha).
  for (double alpha : {10.0, 20.0, 45.0}) {
    const BevelTip tip = bevel(0.5, alpha, 0.0);
    const double r = 0.5 * mm, exact = kPi * r * r * 0.1 * mm + kPi * r * r * r / std::tan(alpha * kPi / 180);
    EXPECT_NEAR(tip.analytic_volume() / exact, 1.0, 1e-12) << alpha;
    EXPECT_NEAR(tip.length(), 0.1 * mm + 2 * r / std::tan(alpha * kPi / 180), 1e-15);
  }
}

TEST(NeedleTip, RoundedTipIsAHemisphereOnTheShaft) {
  const BevelTip tip = bevel(1.25, 10, 1.25);
  ASSERT_TRUE(tip.rounded());
  const double r = 1.25 * mm;
  EXPECT_NEAR(tip.analytic_volume(), kPi * r * r * 0.1 * mm + 2.0 / 3.0 * kPi * r * r * r, 1e-20);
  EXPECT_NEAR(tip.length(), 1.35 * mm, 1e-15);
}

TEST(NeedleTip, FilletGeometryIsTangentAndConvergesToTheSharpTip) {
  const BevelTip tip = bevel(0.83, 10, 0.25);
  // The arc is tangent to the bevel line: the profile is continuous and has the bevel slope there.
  const double x = tip.fillet_tangent_x(), h = 1e-9;
  const double bevel_slope = -1 / std::tan(tip.bevel_rad);
  EXPECT_NEAR((tip.profile_top(x) - tip.profile_top(x - h)) / h, bevel_slope, 1e-3 * std::abs(bevel_slope));
  // Tangent length along the generator equals tau / tan(alpha/2).
  const double sharp_tip_z = 0.1 * mm + 2 * 0.83 * mm / std::tan(tip.bevel_rad);
  EXPECT_NEAR(sharp_tip_z - tip.fillet_centre_z(), 0.25 * mm / std::tan(tip.bevel_rad / 2), 1e-15);
  // A vanishing fillet removes a vanishing volume: a profile area ~ tau^2 at the generator,
  // where the chord 2 sqrt(r^2 - x^2) ~ sqrt(tau), so the volume goes as tau^2.5.
  const double sharp = bevel(0.83, 10, 0).analytic_volume();
  const double d1 = sharp - bevel(0.83, 10, 0.02).analytic_volume(), d2 = sharp - bevel(0.83, 10, 0.01).analytic_volume();
  EXPECT_GT(d1, 0);
  EXPECT_NEAR(std::log2(d1 / d2), 2.5, 0.05);
}

TEST(NeedleTip, CompliantVolumeSumsItsParts) {
  const CompliantTip tip{0.5 * mm, 0.1 * mm, 1 * mm, 0.2 * mm, 3.5 * mm, 0.5 * mm};
  const double r = 0.5 * mm, a = kPi * r * r;
  EXPECT_NEAR(tip.analytic_volume(), a * 0.1 * mm + kPi * 0.01 * mm * mm * 1 * mm + a * 3 * mm + a * 0.5 * mm / 3, 1e-20);
  EXPECT_TRUE(tip.violations().empty());
}

TEST(NeedleTip, EveryTableOneTipIsGeometricallyValid) {
  for (const char* tip : {"radius_mm = 0.32\nbevel_deg = 10\nfillet_mm = 0.15", "radius_mm = 0.5\nbevel_deg = 10\nfillet_mm = 0.15",
                          "radius_mm = 0.5\nbevel_deg = 20\nfillet_mm = 0.25", "radius_mm = 0.83\nbevel_deg = 10\nfillet_mm = 0.15",
                          "radius_mm = 0.83\nbevel_deg = 20\nfillet_mm = 0.25", "radius_mm = 0.83\nbevel_deg = 20\nfillet_mm = 0.45",
                          "radius_mm = 1.25\nbevel_deg = 10\nfillet_mm = 1.25", "radius_mm = 0.83\nbevel_deg = 10\nfillet_mm = 0.25"})
    EXPECT_TRUE(rules_of(std::string("[needle]\n") + tip).empty()) << tip;
}

TEST(NeedleTip, ImpossibleCombinationsNameTheirRule) {
  using Rules = std::vector<std::string>;
  // A 10 deg bevel on r = 1.25 mm is 14.2 mm long: longer than the 12 mm cube.
  EXPECT_EQ(rules_of("[needle]\nradius_mm = 1.25\nbevel_deg = 10\nfillet_mm = 0.15"), Rules{"tip-fits-cube"});
  EXPECT_EQ(rules_of("[needle]\nradius_mm = 0.32\nbevel_deg = 20\nfillet_mm = 0.45"), Rules{"fillet-exceeds-radius"});
  // tau / tan(22.5 deg) = 1.086 mm > 2r / tan(45 deg) = 1.0 mm
  EXPECT_EQ(rules_of("[needle]\nradius_mm = 0.5\nbevel_deg = 45\nfillet_mm = 0.45"), Rules{"fillet-fits-bevel"});
  EXPECT_EQ(rules_of("[needle]\nradius_mm = 1.6\nbevel_deg = 45\nfillet_mm = 0.1"), Rules{"core-contains-needle"});
  EXPECT_EQ(rules_of("[tissue]\ncore_width_mm = 12"), (Rules{"core-inside-cube"}));
  EXPECT_EQ(rules_of("[tissue]\ncore_element_mm = 3"), Rules{"core-finer-than-outside"});
  EXPECT_EQ(rules_of("[needle]\nkind = \"compliant\"\nneck_diameter_mm = 1.0"), Rules{"neck-thinner-than-needle"});
}

TEST(NeedleTip, RequireValidSceneListsEveryViolatedRule) {
  const Case c = Case::parse("[needle]\nradius_mm = 0.32\nfillet_mm = 0.45\n[tissue]\ncore_element_mm = 3", "bad.toml");
  try {
    require_valid_brain_tip_scene(parse_needle_tip_spec(c), parse_tissue_cube_spec(c));
    FAIL();
  } catch (const CaseError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("bad.toml: key 'needle': impossible geometry"), std::string::npos) << m;
    EXPECT_NE(m.find("fillet-exceeds-radius"), std::string::npos) << m;
    EXPECT_NE(m.find("core-finer-than-outside"), std::string::npos) << m;
  }
}

TEST(NeedleTip, TissueRulesAreReportedUnderTheirTissueKey) {
  for (const auto& [toml, key] : {std::pair{"[tissue]\ncore_element_mm = 3", "tissue.core_element_mm"},
                                  std::pair{"[tissue]\ncore_width_mm = 12", "tissue.core_width_mm"}}) {
    try {
      const Case c = Case::parse(toml, "bad.toml");
      require_valid_brain_tip_scene(parse_needle_tip_spec(c), parse_tissue_cube_spec(c));
      FAIL() << toml;
    } catch (const CaseError& e) {
      EXPECT_NE(std::string(e.what()).find(fmt::format("bad.toml: key '{}': impossible geometry", key)),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(NeedleMotion, CaseKeysAndARampLongerThanTheMotionIsACaseError) {
  const NeedleMotion motion = needle_motion_from_spec(parse_motion_spec(Case::parse(
      "[motion]\ninsertion_speed_mm_per_s = 2\nrotation_speed_deg_per_s = 90\nduration_s = 0.2\nramp_s = 0.01\n",
      "motion.toml")));
  EXPECT_DOUBLE_EQ(motion.insertion_speed, 2e-3);
  EXPECT_DOUBLE_EQ(motion.rotation_speed, kPi / 2);
  EXPECT_DOUBLE_EQ(motion.duration, 0.2);
  EXPECT_DOUBLE_EQ(motion.ramp, 0.01);
  try {
    parse_motion_spec(Case::parse("[motion]\nduration_s = 0.1\nramp_s = 0.2\n", "long_ramp.toml"));
    FAIL() << "no CaseError";
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("long_ramp.toml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("motion.ramp_s"), std::string::npos) << e.what();
  }
}
