// Case files: typed keys, ranges, defaults, overrides and the echoed resolved case.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include <nlohmann/json.hpp>

#include "case/case.hpp"
#include "case/schema.hpp"

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
