// Case files: typed keys, ranges, defaults, overrides and the echoed resolved case.
#include <gtest/gtest.h>

#include <array>
#include <optional>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "case/case.hpp"
#include "case/schema.hpp"
#include "case/specs/contact_spec.hpp"
#include "case/specs/insertion_force_spec.hpp"
#include "case/specs/mesh_spec.hpp"
#include "case/specs/output_spec.hpp"
#include "case/specs/prbm_check_spec.hpp"
#include "case/specs/pressure_spec.hpp"
#include "case/specs/steering_spec.hpp"
#include "case/specs/thresholds_spec.hpp"

using needlefem::Case;
using needlefem::CaseError;

namespace {
std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    Case::parse(text, "cases/x.toml", overrides);
  } catch (const CaseError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(Case, DefaultsFillEveryKeyWithADefault) {
  const Case c = Case::parse("", "empty.toml");
  for (const auto& spec : needlefem::case_schema()) {
    if (std::holds_alternative<std::monostate>(spec.fallback)) continue;
    EXPECT_TRUE(c.has(spec.key)) << spec.key;
  }
  EXPECT_DOUBLE_EQ(c.real("tissue.cube_edge_mm"), 12.0);
  EXPECT_DOUBLE_EQ(c.real("tissue.core_element_mm"), 0.4);
  EXPECT_FALSE(c.given("needle.radius_mm"));
}

TEST(Case, ReadsGivenValuesAndIntegersAsReals) {
  const Case c = Case::parse("[needle]\nradius_mm = 1\nbevel_deg = 10.5\n", "a.toml");
  EXPECT_DOUBLE_EQ(c.real("needle.radius_mm"), 1.0);
  EXPECT_DOUBLE_EQ(c.real("needle.bevel_deg"), 10.5);
  EXPECT_TRUE(c.given("needle.radius_mm"));
}

TEST(Case, UnknownKeyNamesFileKeyAndSuggestion) {
  const std::string e = error_of("[needle]\nradius_m = 0.5\n");
  EXPECT_NE(e.find("cases/x.toml"), std::string::npos) << e;
  EXPECT_NE(e.find("'needle.radius_m'"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'needle.radius_mm'"), std::string::npos) << e;
}

TEST(Case, WrongTypeIsRejected) {
  EXPECT_NE(error_of("[needle]\nradius_mm = \"thin\"\n").find("expected a real number, got a string"), std::string::npos);
  EXPECT_NE(error_of("[mesh]\norder = 1.5\n").find("expected an integer"), std::string::npos);
  EXPECT_NE(error_of("[block]\nsize_mm = [1, 2]\n").find("expected 3 numbers, got 2"), std::string::npos);
  EXPECT_NE(error_of("[needle]\nkind = \"spoon\"\n").find("'spoon' is not one of: bevel, compliant"), std::string::npos);
  EXPECT_NE(error_of("needle = 3\n").find("unknown key"), std::string::npos);
  EXPECT_NE(error_of("[groups]\nfixed = \"base\"\n").find("expected a list of strings, got a string"),
            std::string::npos);
  EXPECT_NE(error_of("[groups]\nfixed = [\"base\", 2]\n").find("got an integer in it"), std::string::npos);
}

TEST(Case, ListsOfGroupNamesAreReadAndEchoed) {
  const Case c = Case::parse("[groups]\nroller = [\"x0\", \"z1\"]\n", "a.toml");
  EXPECT_EQ(c.texts("groups.roller"), (std::vector<std::string>{"x0", "z1"}));
  EXPECT_TRUE(c.texts("groups.fixed").empty());
  EXPECT_EQ(Case::parse(c.to_toml(), "echo.toml").texts("groups.roller"), c.texts("groups.roller"));
  EXPECT_EQ(Case::parse("", "a.toml", {"groups.pressure=[\"inner\"]"}).texts("groups.pressure"),
            std::vector<std::string>{"inner"});
}

TEST(Case, OutOfRangeIsRejectedWithTheRange) {
  const std::string e = error_of("[needle]\nradius_mm = -0.5\n");
  EXPECT_NE(e.find("'needle.radius_mm': -0.5 is out of range (0, 100]"), std::string::npos) << e;
  EXPECT_NE(error_of("[mesh]\norder = 3\n").find("out of range [1, 2]"), std::string::npos);
}

// A key whose help gives 0 a meaning ("0 = sharp", "0 gives the plain kink") must accept 0
// (contact.penalty_smoothing said so and rejected it: its range was (0, 100]).
TEST(Case, ZeroIsAcceptedWhereTheHelpGivesItAMeaning) {
  int checked = 0;
  for (const auto& spec : needlefem::case_schema()) {
    if (spec.type != needlefem::KeyType::Real) continue;
    static const std::regex zero_has_a_meaning("(^|[ ;(])0 (=|gives|lets|means|keeps) ");
    if (!std::regex_search(spec.help, zero_has_a_meaning)) continue;
    ++checked;
    EXPECT_EQ(error_of("", {spec.key + "=0"}), "") << spec.key;
  }
  EXPECT_GE(checked, 6);
}

TEST(Case, SyntaxErrorNamesLine) {
  const std::string e = error_of("[needle]\nradius_mm = = 1\n");
  EXPECT_NE(e.find("cases/x.toml:2:"), std::string::npos) << e;
  EXPECT_NE(e.find("TOML syntax error"), std::string::npos) << e;
}

TEST(Case, MissingFileIsAClearError) {
  try {
    Case::load("/nonexistent/case.toml");
    FAIL();
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/case.toml: cannot open case file"), std::string::npos);
  }
}

TEST(Case, OverridesApplyAfterTheFileAndAreValidated) {
  const Case c = Case::parse("[needle]\nradius_mm = 0.5\n", "a.toml", {"needle.radius_mm=0.83", "needle.kind=compliant"});
  EXPECT_DOUBLE_EQ(c.real("needle.radius_mm"), 0.83);
  EXPECT_EQ(c.text("needle.kind"), "compliant");
  EXPECT_NE(error_of("", {"needle.radius_mm=abc"}).find("--set needle.radius_mm=abc"), std::string::npos);
  EXPECT_NE(error_of("", {"needle.radius=1"}).find("unknown key"), std::string::npos);
  EXPECT_NE(error_of("", {"novalue"}).find("expected KEY=VALUE"), std::string::npos);
}

TEST(Case, ResolvedCaseRoundTripsThroughToml) {
  const Case c = Case::parse("[needle]\nradius_mm = 0.83\n[block]\nsize_mm = [1, 2, 3]\n", "a.toml");
  const Case again = Case::parse(c.to_toml(), "echo.toml");
  EXPECT_EQ(again.to_json(), c.to_json());
  EXPECT_DOUBLE_EQ(c.to_json()["needle"]["radius_mm"].get<double>(), 0.83);
}

TEST(Case, CrossKeyErrorsUseTheSameFormat) {
  const Case c = Case::parse("", "b.toml");
  EXPECT_STREQ(c.error("needle.fillet_mm", "too big").what(), "b.toml: key 'needle.fillet_mm': too big");
}

// --- the motion's length: duration, travel or rotation angle ---------------------------------

namespace {
double duration_of(const std::string& motion, const std::vector<std::string>& overrides = {}) {
  return Case::parse("[motion]\n" + motion, "cases/x.toml", overrides).real("motion.duration_s");
}
}  // namespace

TEST(MotionLength, DurationFollowsFromWhicheverStatementIsGiven) {
  EXPECT_DOUBLE_EQ(duration_of(""), 0.1);                                                // the default
  EXPECT_DOUBLE_EQ(duration_of("duration_s = 0.3\n"), 0.3);                              // the old key alone
  EXPECT_DOUBLE_EQ(duration_of("insertion_travel_mm = 0.2\n"), 0.2);                     // at the default 1 mm/s
  EXPECT_DOUBLE_EQ(duration_of("insertion_travel_mm = 0.2\ninsertion_speed_mm_per_s = 4\n"), 0.05);
  EXPECT_DOUBLE_EQ(duration_of("rotation_deg = 36\n"), 0.2);                             // at the default 180 deg/s
  EXPECT_DOUBLE_EQ(duration_of("rotation_deg = -9\nrotation_speed_deg_per_s = -90\n"), 0.1);
  EXPECT_DOUBLE_EQ(duration_of("insertion_travel_mm = 0.1\nrotation_deg = 18\n"), 0.1);  // the paper's motion
  EXPECT_DOUBLE_EQ(duration_of("insertion_travel_mm = 0.1\nrotation_deg = 18\nduration_s = 0.1\n"), 0.1);
  // The start ramp loses half its length of travel: the duration makes it up.
  EXPECT_DOUBLE_EQ(duration_of("insertion_travel_mm = 0.1\nramp_s = 0.02\n"), 0.11);
  // No turn at no rotation speed says nothing about the duration.
  EXPECT_DOUBLE_EQ(duration_of("insertion_travel_mm = 0.1\nrotation_deg = 0\nrotation_speed_deg_per_s = 0\n"), 0.1);
}

TEST(MotionLength, ContradictionsAreOneLineNamingTheKeys) {
  const std::string travel_duration =
      error_of("[motion]\ninsertion_travel_mm = 0.2\ninsertion_speed_mm_per_s = 1\nduration_s = 0.1\n");
  EXPECT_EQ(travel_duration,
            "cases/x.toml: key 'motion.insertion_travel_mm': motion.insertion_travel_mm = 0.2 mm at "
            "motion.insertion_speed_mm_per_s = 1 mm/s takes 0.2 s, but motion.duration_s = 0.1 s");
  const std::string travel_rotation = error_of("[motion]\ninsertion_travel_mm = 0.1\nrotation_deg = 36\n");
  EXPECT_EQ(travel_rotation,
            "cases/x.toml: key 'motion.rotation_deg': motion.rotation_deg = 36 deg at "
            "motion.rotation_speed_deg_per_s = 180 deg/s takes 0.2 s, but motion.insertion_travel_mm = 0.1 mm at "
            "motion.insertion_speed_mm_per_s = 1 mm/s takes 0.1 s");
  EXPECT_NE(error_of("[motion]\ninsertion_travel_mm = 0.1\nramp_s = 0.02\nduration_s = 0.1\n").find("with the start ramp"),
            std::string::npos);
  EXPECT_EQ(error_of("[motion]\ninsertion_travel_mm = 0.1\ninsertion_speed_mm_per_s = 0\n"),
            "cases/x.toml: key 'motion.insertion_travel_mm': 0.1 mm needs a nonzero motion.insertion_speed_mm_per_s");
  EXPECT_NE(error_of("[motion]\nrotation_deg = -18\n").find("key 'motion.rotation_deg': -18 deg is not reached moving at "
                                                           "motion.rotation_speed_deg_per_s = 180 deg/s"),
            std::string::npos);
  for (const auto& e : {travel_duration, travel_rotation}) EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

TEST(MotionLength, AnOverrideRestatesTheLengthAndSpeedsKeepTheDepth) {
  const std::string paper = "insertion_travel_mm = 0.1\nrotation_deg = 18\n";
  EXPECT_DOUBLE_EQ(duration_of(paper, {"motion.duration_s=0.01"}), 0.01);  // shortened: the file's travel dropped
  const Case shortened = Case::parse("[motion]\n" + paper, "cases/x.toml", {"motion.duration_s=0.01"});
  EXPECT_FALSE(shortened.has("motion.insertion_travel_mm"));
  EXPECT_DOUBLE_EQ(duration_of(paper, {"motion.insertion_speed_mm_per_s=2", "motion.rotation_speed_deg_per_s=360"}),
                   0.05);
  EXPECT_DOUBLE_EQ(duration_of("duration_s = 0.1\n", {"motion.insertion_travel_mm=0.3"}), 0.3);
  // Within one layer the statements must agree.
  EXPECT_NE(error_of("", {"motion.duration_s=0.2", "motion.insertion_travel_mm=0.1"}).find("key 'motion.insertion_travel_mm'"),
            std::string::npos);
  // A speed changed alone on a travel-stated case contradicts its rotation angle.
  EXPECT_NE(error_of("[motion]\n" + paper, {"motion.insertion_speed_mm_per_s=2"}).find("but motion.insertion_travel_mm"),
            std::string::npos);
}

TEST(MotionLength, CaseFilesStatingTravelAndRotationKeepTheirMotion) {
  struct Motion {
    const char* file;
    double speed_mm_per_s, rotation_deg_per_s, duration_s;
  };
  // The rate study's and Table I's speeds and durations before they stated the travel and angle.
  for (const Motion& m : {Motion{"rate_study/fast.toml", 2.0, 360.0, 0.05}, Motion{"rate_study/medium.toml", 1.0, 180.0, 0.1},
                          Motion{"rate_study/slow.toml", 0.5, 90.0, 0.2}, Motion{"table1/r0.50_a20_f0.25.toml", 1.0, 180.0, 0.1},
                          Motion{"table1/r1.25_rounded.toml", 1.0, 180.0, 0.1}}) {
    const Case c = Case::load(std::string(NEEDLEFEM_CASES_DIR) + "/" + m.file);
    EXPECT_EQ(c.real("motion.insertion_speed_mm_per_s"), m.speed_mm_per_s) << m.file;
    EXPECT_EQ(c.real("motion.rotation_speed_deg_per_s"), m.rotation_deg_per_s) << m.file;
    EXPECT_EQ(c.real("motion.duration_s"), m.duration_s) << m.file;  // bit for bit
    EXPECT_DOUBLE_EQ(c.real("motion.insertion_travel_mm"), 0.1) << m.file;
    EXPECT_DOUBLE_EQ(c.real("motion.rotation_deg"), 18.0) << m.file;
  }
}

// NEEDLEFEM_SET: the environment's overrides come after --set, restate the motion's length like any
// layer, and name themselves in errors.
TEST(EnvironmentOverrides, ApplyAfterSetAndNameThemselvesInErrors) {
  ASSERT_EQ(setenv(needlefem::kEnvironmentOverrides, "tissue.core_element_mm=1.5  motion.duration_s=0.01", 1), 0);
  const Case c = Case::parse("[tissue]\ncore_element_mm = 0.4\n[motion]\ninsertion_travel_mm = 0.1\n", "a.toml",
                             {"tissue.core_element_mm=0.8", "mesh.seed=3"});
  EXPECT_EQ(c.real("tissue.core_element_mm"), 1.5);
  EXPECT_EQ(c.integer("mesh.seed"), 3);
  EXPECT_EQ(c.real("motion.duration_s"), 0.01);
  EXPECT_FALSE(c.given("motion.insertion_travel_mm"));
  ASSERT_EQ(setenv(needlefem::kEnvironmentOverrides, "tissue.core_elemnt_mm=1.5", 1), 0);
  EXPECT_EQ(error_of(""), "NEEDLEFEM_SET tissue.core_elemnt_mm=1.5: key 'tissue.core_elemnt_mm': unknown key "
                          "(did you mean 'tissue.core_element_mm'?)");
  ASSERT_EQ(unsetenv(needlefem::kEnvironmentOverrides), 0);
  EXPECT_EQ(Case::parse("", "a.toml").real("tissue.core_element_mm"), 0.4);
}

// Each [thresholds] key reaches its own field of ThresholdsSpec: the schema's default where the case
// does not give the key, else the given value (distinct values, so that no two fields swap keys).
TEST(ThresholdsSpec, EachKeyReachesItsOwnFieldWithTheSchemasDefault) {
  using needlefem::ThresholdsSpec;
  const std::pair<std::string, double ThresholdsSpec::*> fields[] = {
      {"log_strain", &ThresholdsSpec::log_strain},
      {"strain_rate_per_s", &ThresholdsSpec::strain_rate_per_s},
      {"stress_pa", &ThresholdsSpec::stress_pa},
      {"critical_distance_mm", &ThresholdsSpec::critical_distance_mm},
      {"strain_rate_window_s", &ThresholdsSpec::strain_rate_window_s},
      {"percentile", &ThresholdsSpec::percentile},
      {"region_mm", &ThresholdsSpec::region_mm}};
  const Case defaults = Case::parse("", "a.toml");
  const ThresholdsSpec by_default = needlefem::parse_thresholds_spec(defaults);
  std::vector<std::string> overrides;
  for (std::size_t i = 0; i < std::size(fields); ++i) {
    const auto& [name, field] = fields[i];
    EXPECT_EQ(by_default.*field, defaults.real("thresholds." + name)) << name;
    overrides.push_back("thresholds." + name + "=" + std::to_string(2 + i));  // inside every key's range
  }
  const ThresholdsSpec given = needlefem::parse_thresholds_spec(Case::parse("", "a.toml", overrides));
  for (std::size_t i = 0; i < std::size(fields); ++i)
    EXPECT_EQ(given.*fields[i].second, 2.0 + i) << fields[i].first;
}

namespace {
// What `parse` makes of the case that gives no key, and of the case `toml` with `overrides`.
template <class Parse>
auto default_and_given_specs(Parse parse, const std::vector<std::string>& overrides, const std::string& toml = "") {
  return std::pair{parse(Case::parse("", "a.toml")), parse(Case::parse(toml, "a.toml", overrides))};
}
}  // namespace

// As for ThresholdsSpec: each key reaches its own field, the schema's default where the case does
// not give it, else the given value (distinct from the default and from the other fields').
TEST(OutputSpec, EachKeyReachesItsOwnFieldWithTheSchemasDefault) {
  const Case defaults = Case::parse("", "a.toml");
  const auto [by_default, given] = default_and_given_specs(
      needlefem::parse_output_spec, {"output.interval_s=2", "output.density_kg_per_m3=3"});
  EXPECT_EQ(by_default.origin, "a.toml");
  EXPECT_EQ(by_default.interval_s, defaults.real("output.interval_s"));
  EXPECT_EQ(by_default.density_kg_per_m3, defaults.real("output.density_kg_per_m3"));
  EXPECT_EQ(given.interval_s, 2.0);
  EXPECT_EQ(given.density_kg_per_m3, 3.0);
}

TEST(PressureSpec, EachKeyReachesItsOwnFieldWithTheSchemasDefault) {
  const Case defaults = Case::parse("", "a.toml");
  ASSERT_TRUE(defaults.flag("pressure.follower"));  // so that the case below gives another value
  const auto [by_default, given] = default_and_given_specs(
      needlefem::parse_pressure_spec, {"pressure.value_pa=2", "pressure.follower=false"},
      "[groups]\npressure = [\"inner\", \"outer\"]\n");
  EXPECT_EQ(by_default.groups, defaults.texts("groups.pressure"));
  EXPECT_EQ(by_default.value_pa, defaults.real("pressure.value_pa"));
  EXPECT_EQ(by_default.follower, defaults.flag("pressure.follower"));
  EXPECT_EQ(given.groups, (std::vector<std::string>{"inner", "outer"}));
  EXPECT_EQ(given.value_pa, 2.0);
  EXPECT_FALSE(given.follower);
}

TEST(NeedleDeflectionCheckSpec, EachKeyReachesItsOwnFieldWithTheSchemasDefault) {
  const Case defaults = Case::parse("", "a.toml");
  ASSERT_FALSE(defaults.flag("needle.deflection_check"));  // so that the case below gives another value
  const auto [by_default, given] = default_and_given_specs(
      needlefem::parse_needle_deflection_check_spec,
      {"needle.deflection_check=true", "needle.youngs_modulus_gpa=2", "needle.poisson_ratio=0.3"});
  EXPECT_EQ(by_default.origin, "a.toml");
  EXPECT_EQ(by_default.enabled, defaults.flag("needle.deflection_check"));
  EXPECT_EQ(by_default.youngs_modulus_gpa, defaults.real("needle.youngs_modulus_gpa"));
  EXPECT_EQ(by_default.poisson_ratio, defaults.real("needle.poisson_ratio"));
  EXPECT_TRUE(given.enabled);
  EXPECT_EQ(given.youngs_modulus_gpa, 2.0);
  EXPECT_EQ(given.poisson_ratio, 0.3);
}

// As for ThresholdsSpec, over the [steering] keys: the schedule's tables are absent unless given.
TEST(SteeringSpec, EachKeyReachesItsOwnFieldWithTheSchemasDefault) {
  using needlefem::SteeringSpec;
  const std::pair<std::string, double SteeringSpec::*> fields[] = {
      {"neck_youngs_modulus_gpa", &SteeringSpec::neck_youngs_modulus_gpa},
      {"tissue_spring_constant_n_per_m2", &SteeringSpec::tissue_spring_constant_n_per_m2},
      {"force_angle_deg", &SteeringSpec::force_angle_deg},
      {"max_turning_angle_deg", &SteeringSpec::max_turning_angle_deg},
      {"magnet_residual_flux_density_t", &SteeringSpec::magnet_residual_flux_density_t},
      {"magnet_pole_width_mm", &SteeringSpec::magnet_pole_width_mm},
      {"magnet_pole_length_mm", &SteeringSpec::magnet_pole_length_mm},
      {"magnet_thickness_mm", &SteeringSpec::magnet_thickness_mm},
      {"magnet_correction_factor", &SteeringSpec::magnet_correction_factor},
      {"insertion_depth_mm", &SteeringSpec::insertion_depth_mm},
      {"insertion_speed_mm_per_s", &SteeringSpec::insertion_speed_mm_per_s},
      {"depth_step_mm", &SteeringSpec::depth_step_mm},
      {"obstacle_radius_mm", &SteeringSpec::obstacle_radius_mm},
      {"target_tolerance_mm", &SteeringSpec::target_tolerance_mm}};
  const std::pair<std::string, std::optional<std::vector<double>> SteeringSpec::*> tables[] = {
      {"schedule_depth_mm", &SteeringSpec::schedule_depth_mm},
      {"schedule_time_s", &SteeringSpec::schedule_time_s},
      {"magnet_distance_mm", &SteeringSpec::magnet_distance_mm},
      {"pull_azimuth_deg", &SteeringSpec::pull_azimuth_deg}};
  const Case defaults = Case::parse("", "a.toml");
  const SteeringSpec by_default = needlefem::parse_steering_spec(defaults);
  std::vector<std::string> overrides{"steering.block_size_mm=[2, 3, 4]", "steering.target_mm=[5, 6, 7]"};
  for (std::size_t i = 0; i < std::size(fields); ++i) {
    const auto& [name, field] = fields[i];
    EXPECT_EQ(by_default.*field, defaults.real("steering." + name)) << name;
    overrides.push_back("steering." + name + "=" + std::to_string((i + 1) / 100.0));  // inside every key's range
  }
  for (std::size_t i = 0; i < std::size(tables); ++i) {
    const auto& [name, table] = tables[i];
    EXPECT_FALSE(by_default.*table) << name;
    overrides.push_back("steering." + name + "=[" + std::to_string(10 + i) + "]");
  }
  const std::vector<double> block = defaults.reals("steering.block_size_mm"), target = defaults.reals("steering.target_mm");
  EXPECT_EQ(by_default.block_size_mm, (std::array{block[0], block[1], block[2]}));
  EXPECT_EQ(by_default.target_mm, (std::array{target[0], target[1], target[2]}));
  const SteeringSpec given = needlefem::parse_steering_spec(Case::parse("", "a.toml", overrides));
  for (std::size_t i = 0; i < std::size(fields); ++i)
    EXPECT_EQ(given.*fields[i].second, (i + 1) / 100.0) << fields[i].first;
  for (std::size_t i = 0; i < std::size(tables); ++i)
    EXPECT_EQ(given.*tables[i].second, std::vector<double>{10.0 + i}) << tables[i].first;
  EXPECT_EQ(given.block_size_mm, (std::array{2.0, 3.0, 4.0}));
  EXPECT_EQ(given.target_mm, (std::array{5.0, 6.0, 7.0}));
}

TEST(PrbmCheckSpec, EachKeyReachesItsOwnFieldWithTheSchemasDefault) {
  const Case defaults = Case::parse("", "a.toml");
  const auto [by_default, given] = default_and_given_specs(
      needlefem::parse_prbm_check_spec,
      {"prbm_check.angles_deg=[3, 1]", "steering.neck_youngs_modulus_gpa=2", "prbm_check.poisson_ratio=0.25",
       "prbm_check.tolerance_percent=4", "prbm_check.element_mm=5", "prbm_check.neck_element_mm=6"});
  EXPECT_EQ(by_default.angles_deg, defaults.reals("prbm_check.angles_deg"));
  EXPECT_EQ(by_default.neck_youngs_modulus_gpa, defaults.real("steering.neck_youngs_modulus_gpa"));
  EXPECT_EQ(by_default.poisson_ratio, defaults.real("prbm_check.poisson_ratio"));
  EXPECT_EQ(by_default.tolerance_percent, defaults.real("prbm_check.tolerance_percent"));
  EXPECT_EQ(by_default.element_mm, defaults.real("prbm_check.element_mm"));
  EXPECT_EQ(by_default.neck_element_mm, defaults.real("prbm_check.neck_element_mm"));
  EXPECT_EQ(given.angles_deg, (std::vector<double>{3.0, 1.0}));  // as given: the check sorts them
  EXPECT_EQ(given.neck_youngs_modulus_gpa, 2.0);
  EXPECT_EQ(given.poisson_ratio, 0.25);
  EXPECT_EQ(given.tolerance_percent, 4.0);
  EXPECT_EQ(given.element_mm, 5.0);
  EXPECT_EQ(given.neck_element_mm, 6.0);
}

TEST(InsertionForceSpec, EachKeyReachesItsOwnFieldWithTheSchemasDefault) {
  const Case defaults = Case::parse("", "a.toml");
  const auto [by_default, given] = default_and_given_specs(
      needlefem::parse_insertion_force_spec,
      {"insertion_force.energy_history=\"h.csv\"", "insertion_force.energy_case=\"e.toml\"",
       "insertion_force.extrapolation_warn_factor=3", "insertion_force.extrapolation_limit_factor=4",
       "insertion_force.fracture_toughness_j_per_m2=5", "insertion_force.rupture_force_n=6",
       "insertion_force.shaft_friction_n_per_mm=7", "insertion_force.travel_mm=8",
       "insertion_force.sample_interval_s=9", "motion.insertion_speed_mm_per_s=10"});
  EXPECT_TRUE(by_default.energy_history.empty());
  EXPECT_TRUE(by_default.energy_case.empty());
  EXPECT_EQ(by_default.extrapolation_warn_factor, defaults.real("insertion_force.extrapolation_warn_factor"));
  EXPECT_EQ(by_default.extrapolation_limit_factor, defaults.real("insertion_force.extrapolation_limit_factor"));
  EXPECT_EQ(by_default.fracture_toughness_j_per_m2, defaults.real("insertion_force.fracture_toughness_j_per_m2"));
  EXPECT_FALSE(by_default.rupture_force_n);  // the schema gives it no default
  EXPECT_EQ(by_default.shaft_friction_n_per_mm, defaults.real("insertion_force.shaft_friction_n_per_mm"));
  EXPECT_EQ(by_default.travel_mm, defaults.real("insertion_force.travel_mm"));
  EXPECT_EQ(by_default.sample_interval_s, defaults.real("insertion_force.sample_interval_s"));
  EXPECT_EQ(by_default.insertion_speed_mm_per_s, defaults.real("motion.insertion_speed_mm_per_s"));
  EXPECT_EQ(given.energy_history.filename(), "h.csv");
  EXPECT_EQ(given.energy_case.filename(), "e.toml");
  EXPECT_EQ(given.extrapolation_warn_factor, 3.0);
  EXPECT_EQ(given.extrapolation_limit_factor, 4.0);
  EXPECT_EQ(given.fracture_toughness_j_per_m2, 5.0);
  EXPECT_EQ(given.rupture_force_n, 6.0);
  EXPECT_EQ(given.shaft_friction_n_per_mm, 7.0);
  EXPECT_EQ(given.travel_mm, 8.0);
  EXPECT_EQ(given.sample_interval_s, 9.0);
  EXPECT_EQ(given.insertion_speed_mm_per_s, 10.0);
}

// The mesh spec's keys that reach the mesh report and the summary beside the mesher.
TEST(MeshSpec, PartitionsRefinementLevelAndEdgeElementsReachTheirFieldsWithTheSchemasDefault) {
  const Case defaults = Case::parse("", "a.toml");
  const auto [by_default, given] = default_and_given_specs(
      needlefem::parse_mesh_spec, {"mesh.partitions=3", "mesh.refinement_level=2", "mesh.edge_elements_per_radius=2"});
  EXPECT_EQ(by_default.partitions, defaults.integer("mesh.partitions"));
  EXPECT_EQ(by_default.refinement_level, defaults.integer("mesh.refinement_level"));
  EXPECT_FALSE(by_default.edge_elements_per_radius.has_value());  // the mesher's, by the tip
  EXPECT_EQ(given.partitions, 3);
  EXPECT_EQ(given.refinement_level, 2);
  EXPECT_EQ(given.edge_elements_per_radius, 2);
}

