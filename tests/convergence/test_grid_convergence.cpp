// convergence/grid_convergence.hpp on sequences with a known answer, and
// convergence/convergence_report.hpp on synthetic summaries, convergence/history_bands.hpp on
// synthetic histories.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "convergence/convergence_report.hpp"
#include "convergence/grid_convergence.hpp"
#include "convergence/history_bands.hpp"
#include "output/csv.hpp"

namespace needlefem::convergence {
namespace {

// f(h) = f* + C h^p on h = 1, 1/2, 1/4 (r = 2) gives back p and f* exactly.
class KnownOrder : public ::testing::TestWithParam<double> {};

TEST_P(KnownOrder, RecoversOrderAndLimit) {
  const double p = GetParam(), exact = 0.25, c = 0.3;
  const auto f = [&](double h) { return exact + c * std::pow(h, p); };
  const Estimate e = estimate(f(1.0), f(0.5), f(0.25));
  EXPECT_EQ(e.behaviour, Behaviour::monotone);
  EXPECT_NEAR(e.observed_order, p, 1e-10);
  EXPECT_EQ(e.order, e.observed_order);
  EXPECT_NEAR(e.extrapolated, exact, 1e-10);
  EXPECT_TRUE(e.note.empty()) << e.note;
  // The band holds the exact value: GCI = 1.25 |e21/f1| / (r^p - 1) = 1.25 |f1 - f*| / |f1|.
  EXPECT_NEAR(e.half_width, 1.25 * (f(0.25) - exact), 1e-12);
  EXPECT_LT(e.band_low, exact);
}

INSTANTIATE_TEST_SUITE_P(Orders, KnownOrder, ::testing::Values(1.0, 2.0, 1.5));

// Hand computation: f = 1.0, 0.9, 0.875: e32 = 0.1, e21 = 0.025, p = ln 4 / ln 2 = 2,
// f_ext = (4 * 0.875 - 0.9)/3 = 0.8666..., GCI = 1.25 * 0.025/0.875 / 3 = 0.0119047619...
TEST(GridConvergence, GciByHand) {
  const Estimate e = estimate(1.0, 0.9, 0.875);
  EXPECT_NEAR(e.observed_order, 2.0, 1e-12);
  EXPECT_NEAR(e.extrapolated, 2.6 / 3.0, 1e-12);
  EXPECT_NEAR(e.gci_fine, 0.011904761904761904, 1e-12);
  EXPECT_NEAR(e.band_low, 0.875 - 0.03125 / 3.0, 1e-12);
  EXPECT_NEAR(e.band_high, 0.875 + 0.03125 / 3.0, 1e-12);
  EXPECT_EQ(order_text(e), "2");
}

// An observed order above the formal 2 is used as 2 in f_ext, and from 2.05 on the band is at
// least 1.25 times the data range (Eça & Hoekstra); one below 0.5 is kept (raising it would
// narrow the band) with Fs = 3.
TEST(GridConvergence, OrderOutsideAsymptoticRange) {
  const Estimate e = estimate(1.09, 1.01, 1.0);  // e32 = 0.08, e21 = 0.01: p = 3
  EXPECT_NEAR(e.observed_order, 3.0, 1e-10);
  EXPECT_EQ(e.order, 2.0);
  EXPECT_NEAR(e.extrapolated, (4.0 * 1.0 - 1.01) / 3.0, 1e-12);
  EXPECT_NEAR(e.half_width, 1.25 * 0.09, 1e-12);  // not 1.25 * 0.01 / 3
  EXPECT_NE(e.note.find("above the formal"), std::string::npos) << e.note;
  EXPECT_NE(e.note.find("data range"), std::string::npos) << e.note;
  // Just above 2 (e32 = 4.1 e21: p = 2.036 < 2.05) the band is the GCI's at p = 2.
  const Estimate near_formal = estimate(1.0 + 0.041 + 0.01, 1.01, 1.0);
  EXPECT_GT(near_formal.observed_order, 2.0);
  EXPECT_LT(near_formal.observed_order, 2.05);
  EXPECT_NEAR(near_formal.half_width, 1.25 * 0.01 / 3.0, 1e-12);
  EXPECT_EQ(near_formal.note.find("data range"), std::string::npos) << near_formal.note;
  const Estimate slow = estimate(1.0, 0.5, 0.1);  // e32 = 0.5, e21 = 0.4: r^p = 1.25, p = 0.32
  EXPECT_NEAR(slow.observed_order, std::log2(1.25), 1e-12);
  EXPECT_EQ(slow.order, slow.observed_order);
  EXPECT_NEAR(slow.extrapolated, (1.25 * 0.1 - 0.5) / 0.25, 1e-12);
  EXPECT_NEAR(slow.half_width, 3.0 * 0.4 / 0.25, 1e-12);
  EXPECT_NE(slow.note.find("not in the asymptotic range"), std::string::npos) << slow.note;
}

TEST(GridConvergence, OscillatoryHasSpreadBand) {
  const Estimate e = estimate(1.0, 1.2, 1.1);  // e32 = -0.2, e21 = 0.1: R < 0
  EXPECT_EQ(e.behaviour, Behaviour::oscillatory);
  EXPECT_EQ(order_text(e), "oscillatory");
  EXPECT_TRUE(std::isnan(e.extrapolated));
  EXPECT_NEAR(e.half_width, 3.0 * 0.2 / 2.0, 1e-12);
  EXPECT_NEAR(e.band_low, 0.8, 1e-12);
  EXPECT_NEAR(e.band_high, 1.4, 1e-12);
}

TEST(GridConvergence, DivergentHasSpreadBand) {
  const Estimate e = estimate(1.0, 1.01, 1.1);  // the differences grow
  EXPECT_EQ(e.behaviour, Behaviour::divergent);
  EXPECT_NEAR(e.half_width, 3.0 * 0.1 / 2.0, 1e-12);
}

TEST(GridConvergence, MeshIndependentQuantity) {
  for (const Estimate& e : {estimate(0.3, 0.3, 0.3), estimate(0.3 * (1 + 1e-14), 0.3, 0.3 * (1 - 1e-14)),
                            estimate(0.0, 0.0, 0.0)}) {
    EXPECT_EQ(e.behaviour, Behaviour::converged);
    EXPECT_EQ(order_text(e), "n/a");
    EXPECT_EQ(e.gci_fine, 0.0);
    EXPECT_EQ(e.band_low, e.fine);
    EXPECT_EQ(e.band_high, e.fine);
    EXPECT_EQ(e.extrapolated, e.fine);
  }
}

TEST(GridConvergence, Verdicts) {
  const Estimate e = estimate(1.0, 0.9, 0.875);  // band [0.8646, 0.8854]
  EXPECT_EQ(verdict(e, 0.9), Verdict::pass);
  EXPECT_EQ(verdict(e, 0.85), Verdict::fail);
  EXPECT_EQ(verdict(e, 0.88), Verdict::undecided);
  EXPECT_EQ(verdict(estimate(1.0, NAN, 0.875), 0.9), Verdict::undecided);
  EXPECT_EQ(verdict(estimate(0.1, 0.1, 0.1), 0.1), Verdict::undecided);  // on the limit
}

nlohmann::json summary(double point_max, double critical, double volume, bool with_safety) {
  nlohmann::json s = {{"status", "completed"},
                      {"max", {{"log_strain", {{"value", point_max}}}, {"principal_stress_pa", {{"value", 10.0}}}}},
                      {"thresholds",
                       {{"log_strain", {{"limit", 0.19}, {"max", point_max}, {"pass", true}, {"max_key", "log_strain"}}}}},
                      {"needle", {{"max_axial_force_n", 0.01}}},
                      {"mesh", {{"tets", 1000}}}};
  if (with_safety)
    s["safety"] = {{"settings", {{"critical_distance_mm", 0.25}}},
                   {"log_strain",
                    {{"limit", 0.19},
                     {"point_max", {{"value", point_max}}},
                     {"critical_distance", {{"value", critical}}},
                     {"volume_above_limit_mm3", {{"value", volume}}},
                     {"history_columns", {{"critical_distance", "critical_distance_log_strain"},
                                          {"point_max", "max_log_strain"}}},
                     {"verdict", "pass"}}}};
  return s;
}

// The critical-distance value decides although the point maximum's band holds the limit.
TEST(ConvergenceReport, CriticalDistanceDecides) {
  std::vector<LevelRun> levels;
  const double point_max[] = {0.15, 0.17, 0.18}, critical[] = {0.12, 0.105, 0.1};
  for (int l = 0; l < 3; ++l)
    levels.push_back({l, "level_" + std::to_string(l), "completed", "", summary(point_max[l], critical[l], 0.0, true)});
  const Report report = build_report(levels);
  ASSERT_EQ(report.limits.size(), 1u);
  EXPECT_EQ(report.limits[0].metric, "safety.log_strain.critical_distance");
  EXPECT_EQ(report.limits[0].verdict, Verdict::pass);
  EXPECT_NEAR(report.limits[0].limit, 0.19, 0.0);
  const auto& rows = report.rows;
  const auto row = [&](const std::string& metric) {
    return std::find_if(rows.begin(), rows.end(), [&](const MetricRow& r) { return r.metric == metric; });
  };
  ASSERT_NE(row("max.log_strain"), rows.end());
  EXPECT_EQ(*row("max.log_strain")->verdict, Verdict::undecided);  // 0.18 + 1.25 * 0.01 / 1 > 0.19
  ASSERT_NE(row("safety.log_strain.volume_above_limit_mm3"), rows.end());
  EXPECT_FALSE(row("safety.log_strain.volume_above_limit_mm3")->verdict.has_value());
  EXPECT_EQ(row("safety.log_strain.volume_above_limit_mm3")->estimate.behaviour, Behaviour::converged);
  EXPECT_FALSE(row("max.principal_stress_pa")->verdict.has_value());
  EXPECT_NE(row("needle.max_axial_force_n"), rows.end());
  const std::string csv = report_csv(report);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "metric,limit,limit_value,f_level0,f_level1,f_level2,observed_order,f_extrapolated,gci_fine,band_low,"
            "band_high,verdict,note");
  EXPECT_NE(verdict_line(report).find("converge: PASS"), std::string::npos) << verdict_line(report);
  // The limit's history columns, as its summaries name them, for converge_history.csv's readers.
  EXPECT_EQ(report_json(report)["verdicts"]["log_strain"]["history_columns"],
            nlohmann::json({{"critical_distance", "critical_distance_log_strain"}, {"point_max", "max_log_strain"}}));
  ASSERT_EQ(report.warnings.size(), 1u);  // every level has 1000 tets
  EXPECT_NE(report.warnings[0].find("same mesh"), std::string::npos) << report.warnings[0];
}

// A level whose tet count grows by less than r^3 is flagged; one that grows by r^3 is not.
TEST(ConvergenceReport, EffectiveRatioWarning) {
  std::vector<LevelRun> levels;
  const int tets[] = {1000, 8000, 20000};  // ratios 2 and 1.36
  for (int l = 0; l < 3; ++l) {
    levels.push_back({l, "", "completed", "", summary(0.1, 0, 0, false)});
    levels.back().summary["mesh"]["tets"] = tets[l];
  }
  const Report report = build_report(levels);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_EQ(report.warnings[0].rfind("level 2: effective refinement ratio", 0), 0u) << report.warnings[0];
  EXPECT_NEAR(report_json(report)["levels"][2]["effective_ratio_to_previous"].get<double>(), std::cbrt(2.5), 1e-12);
}

// Without "safety" the point maximum decides; a failed level leaves its values empty.
TEST(ConvergenceReport, PointMaximumFallbackAndFailedLevel) {
  std::vector<LevelRun> levels;
  for (int l = 0; l < 3; ++l) levels.push_back({l, "", "completed", "", summary(0.3, 0, 0, false)});
  Report report = build_report(levels);
  ASSERT_EQ(report.limits.size(), 1u);
  EXPECT_EQ(report.limits[0].metric, "max.log_strain");
  EXPECT_EQ(report.limits[0].verdict, Verdict::fail);
  levels[1] = {1, "", "failed", "diverged", nullptr};
  report = build_report(levels);
  EXPECT_EQ(report.limits[0].verdict, Verdict::undecided);
  EXPECT_EQ(report.rows[0].estimate.behaviour, Behaviour::incomplete);
  EXPECT_TRUE(std::isnan(report.rows[0].values[1]));
  EXPECT_EQ(report_json(report)["levels"][1]["error"], "diverged");
}

// Four levels: each band of the three levels below the finest is checked against the finest
// value. A second-order sequence (f = 0.1 + 0.08 h², h = 1, 1/2, 1/4, 1/8) lands inside its
// band one level up; a finest value that jumps by ten times the last difference does not.
TEST(ConvergenceReport, BandOfTheCoarserLevelsCheckedAgainstTheFinest) {
  const auto levels_with = [](double finest_critical) {
    std::vector<LevelRun> levels;
    for (int l = 0; l < 4; ++l) {
      const double h = std::ldexp(1.0, -l), critical = l == 3 ? finest_critical : 0.1 + 0.08 * h * h;
      levels.push_back({l, "", "completed", "", summary(0.15, critical, 0.0, true)});
      levels.back().summary["mesh"]["tets"] = 1000 << (3 * l);
    }
    return levels;
  };
  const auto critical_row = [](const Report& report) {
    return *std::find_if(report.rows.begin(), report.rows.end(),
                         [](const MetricRow& r) { return r.metric == "safety.log_strain.critical_distance"; });
  };
  const Report smooth = build_report(levels_with(0.1 + 0.08 / 64));
  const MetricRow held = critical_row(smooth);
  ASSERT_TRUE(held.coarser_estimate.has_value());
  // Levels 0-2: p = 2, GCI half-width 1.25 |e21| / 3 = 1.25 * 0.015 / 3 around 0.105.
  EXPECT_NEAR(held.coarser_estimate->band_low, 0.105 - 1.25 * 0.015 / 3, 1e-12);
  EXPECT_NEAR(held.coarser_estimate->band_high, 0.105 + 1.25 * 0.015 / 3, 1e-12);
  ASSERT_TRUE(held.finest_in_coarser_band.has_value());
  EXPECT_TRUE(*held.finest_in_coarser_band);
  // Every row with values on all four levels is checked (the volume is mesh-independent: its band
  // is the point itself, which the equal finest value lies in).
  EXPECT_EQ(smooth.coarser_bands_checked, static_cast<int>(smooth.rows.size()));
  EXPECT_EQ(smooth.coarser_bands_held, smooth.coarser_bands_checked);
  EXPECT_NE(coarser_band_line(smooth).find("hold level 3's value for"), std::string::npos) << coarser_band_line(smooth);
  const std::string csv = report_csv(smooth);
  EXPECT_NE(csv.substr(0, csv.find('\n')).find(",note,coarser_band_low,coarser_band_high,finest_in_coarser_band"),
            std::string::npos);

  const Report jumped = build_report(levels_with(0.1 + 0.08 / 16 - 10 * (0.08 / 16 - 0.08 / 64)));
  const MetricRow missed = critical_row(jumped);
  ASSERT_TRUE(missed.finest_in_coarser_band.has_value());
  EXPECT_FALSE(*missed.finest_in_coarser_band);
  EXPECT_EQ(jumped.coarser_bands_held, jumped.coarser_bands_checked - 1);
  EXPECT_NE(coarser_band_line(jumped).find("not safety.log_strain.critical_distance"), std::string::npos)
      << coarser_band_line(jumped);
  EXPECT_EQ(report_json(jumped)["coarser_bands"]["held"], jumped.coarser_bands_checked - 1);
  // Three levels: nothing to check one level up.
  std::vector<LevelRun> three = levels_with(0.1);
  three.pop_back();
  const Report report3 = build_report(three);
  EXPECT_FALSE(report3.rows[0].coarser_estimate.has_value());
  EXPECT_EQ(coarser_band_line(report3), "");
  EXPECT_FALSE(report_json(report3).contains("coarser_bands"));
}

// A converge table read back (report_from_table) gives the report it was written from: the same
// values, estimates, verdicts and check one level up; a note with commas and quotes survives
// the CSV; a table with a band made under other rules gets this version's band; and a text that
// is not a converge table is refused in one line naming the file.
TEST(ConvergenceReport, TableReadBackIsTheSameReport) {
  std::vector<LevelRun> levels;
  const double point_max[] = {0.15, 0.17, 0.18, 0.185}, critical[] = {0.12, 0.105, 0.1, 0.099};
  for (int l = 0; l < 4; ++l) {
    levels.push_back({l, "", "completed", "", summary(point_max[l], critical[l], 0.002 * (4 - l), true)});
    levels.back().summary["mesh"]["tets"] = 1000 << (3 * l);
  }
  const Report written = build_report(levels);
  const Report read = report_from_table(report_csv(written), "converge.csv");
  ASSERT_EQ(read.levels.size(), 4u);
  EXPECT_EQ(read.levels[3].level, 3);
  ASSERT_EQ(read.rows.size(), written.rows.size());
  for (std::size_t i = 0; i < read.rows.size(); ++i) {
    const MetricRow &a = written.rows[i], &b = read.rows[i];
    EXPECT_EQ(b.metric, a.metric);
    EXPECT_EQ(b.compared, a.compared) << a.metric;
    for (std::size_t l = 0; l < 4; ++l) EXPECT_NEAR(b.values[l], a.values[l], 1e-8 * std::abs(a.values[l])) << a.metric;
    EXPECT_NEAR(b.estimate.half_width, a.estimate.half_width, 1e-7 * std::abs(a.estimate.fine)) << a.metric;
    EXPECT_EQ(b.estimate.note, a.estimate.note);
    EXPECT_EQ(b.verdict, a.verdict) << a.metric;
    EXPECT_EQ(b.finest_in_coarser_band, a.finest_in_coarser_band) << a.metric;
  }
  ASSERT_EQ(read.limits.size(), 1u);
  EXPECT_EQ(read.limits[0].metric, "safety.log_strain.critical_distance");
  EXPECT_EQ(verdict_line(read), verdict_line(written));
  EXPECT_EQ(coarser_band_line(read), coarser_band_line(written));

  // The same fields, read as csv_field wrote them.
  const std::string note = "a note, with \"quotes\", and commas";
  EXPECT_EQ(output::csv_record("x," + output::csv_field(note) + ",,1"),
            (std::vector<std::string>{"x", note, "", "1"}));

  // Levels 0.12 / 0.105 / 0.1 of a table whose gci_fine says 0.1 %: p = 1.58, this version's band.
  const std::string stale =
      "metric,limit,limit_value,f_level0,f_level1,f_level2,observed_order,f_extrapolated,gci_fine,band_low,band_high,"
      "verdict,note\nsafety.log_strain.critical_distance,log_strain,0.19,0.12,0.105,0.1,9,0.1,0.001,0.0999,0.1001,fail,"
      "\"old, rules\"\n";
  const Report again = report_from_table(stale, "stale.csv");
  const Estimate expected = estimate(0.12, 0.105, 0.1);
  EXPECT_NEAR(again.rows.at(0).estimate.half_width, expected.half_width, 1e-15);
  EXPECT_EQ(*again.rows.at(0).verdict, Verdict::pass);

  const auto refusal = [](const std::string& text) {
    try {
      report_from_table(text, "t.csv");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refusal(""), "t.csv: empty: not a converge table");
  EXPECT_EQ(refusal("metric,limit,limit_value,f_level0,f_level1,verdict\n"),
            "t.csv: 2 level columns f_levelK: grid convergence needs three");
  EXPECT_EQ(refusal("metric,limit_value,f_level0,f_level1,f_level2,verdict\n"), "t.csv: no column limit (not a converge table)");
  EXPECT_EQ(refusal("metric,limit,limit_value,f_level0,f_level1,f_level2,verdict\nm,,,1,x,3,\n"),
            "t.csv: metric m: column f_level1: 'x' is not a number");
  EXPECT_EQ(refusal("metric,limit,limit_value,f_level0,f_level1,f_level2,verdict\nm,,,1,2\n"),
            "t.csv: row 2: 5 fields, the header has 7");
}

// Histories on h = 1, 1/2, 1/4 whose critical-distance value is g(t) + 0.08 h² t: at every time
// the order 2 and the band 1.25 |e21| / 3 around the finest value; the counters and the maxima's
// positions are not quantities; a time one level lacks is incomplete there, and a time written
// to fewer digits is matched.
TEST(HistoryBands, BandAtEveryOutputTime) {
  const auto history = [](int level, const std::vector<double>& times) {
    output::HistoryTable table;
    table.columns = {"time_s", "steps", "newton_iterations", "critical_distance_log_strain",
                     "max_log_strain_x_mm"};
    const double h = std::ldexp(1.0, -level);
    for (double t : times) table.rows.push_back({t, 10.0 * t, 20.0 * t, 0.2 * t + 0.08 * h * h * t, h});
    return table;
  };
  const std::vector<output::HistoryTable> histories{history(0, {0.0, 0.5000000001}), history(1, {0.0, 0.5, 1.0}),
                                                     history(2, {0.0, 0.5, 1.0})};
  const HistoryBands bands = history_bands({0, 1, 2}, histories);
  ASSERT_EQ(bands.rows.size(), 3u) << "one quantity at three times";
  for (const auto& row : bands.rows) EXPECT_EQ(row.quantity, "critical_distance_log_strain");
  EXPECT_EQ(bands.rows[0].estimate.behaviour, Behaviour::converged) << "all zero at t = 0";
  const HistoryBandRow& half = bands.rows[1];
  EXPECT_DOUBLE_EQ(half.time_s, 0.5);
  ASSERT_EQ(half.estimate.behaviour, Behaviour::monotone);
  EXPECT_NEAR(half.estimate.observed_order, 2.0, 1e-6);
  EXPECT_NEAR(half.estimate.extrapolated, 0.1, 1e-9);
  const double e21 = 0.08 * 0.5 * (0.25 - 0.0625);
  EXPECT_NEAR(half.estimate.half_width, 1.25 * e21 / 3.0, 1e-10);
  EXPECT_EQ(bands.rows[2].estimate.behaviour, Behaviour::incomplete) << "level 0 has no t = 1";
  EXPECT_TRUE(std::isnan(bands.rows[2].values[0]));

  const std::string csv = history_bands_csv(bands);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "quantity,time_s,f_level0,f_level1,f_level2,observed_order,f_extrapolated,gci_fine,band_low,band_high,note,"
            "peak_time_s,change_since_peak,change_band_low,change_band_high,change_resolution");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);
  EXPECT_NE(csv.find("\ncritical_distance_log_strain,0.5,0.14,0.11,0.1025,2,0.1,"), std::string::npos) << csv;
}

// A curve that falls after its peak at t = 0.1, on h = 1, 1/2, 1/4: f = g(t) + a(t) h², with
// g = 1.0, 0.96, 0.95 and a = 0.4, 0.4, 0.6. At t = 0.2 the two times' bands overlap, but every
// level's error is the same at both times, so the change since the peak is mesh-independent:
// -0.04, resolved below the peak. At t = 0.3 the change's error is 0.2 h², order 2, and its band by hand
// is -0.0375 +- 1.25 (0.05 - 0.0125) / 3.
TEST(HistoryBands, ChangeSincePeakHasItsOwnBand) {
  const std::vector<double> times{0.1, 0.2, 0.3}, g{1.0, 0.96, 0.95}, a{0.4, 0.4, 0.6};
  std::vector<output::HistoryTable> histories;
  for (int level = 0; level < 3; ++level) {
    output::HistoryTable table;
    table.columns = {"time_s", "critical_distance_strain_rate_per_s"};
    const double h = std::ldexp(1.0, -level);
    for (std::size_t t = 0; t < times.size(); ++t) table.rows.push_back({times[t], g[t] + a[t] * h * h});
    histories.push_back(std::move(table));
  }
  const HistoryBands bands = history_bands({0, 1, 2}, histories);
  ASSERT_EQ(bands.rows.size(), 3u);
  for (const auto& row : bands.rows) EXPECT_DOUBLE_EQ(row.peak_time_s, 0.1);
  EXPECT_STREQ(change_resolution(bands.rows[0]), "") << "the peak itself";
  const HistoryBandRow& overlap = bands.rows[1];
  EXPECT_GT(overlap.estimate.band_high, bands.rows[0].estimate.band_low) << "the two times' bands overlap";
  EXPECT_EQ(overlap.change.behaviour, Behaviour::converged);
  EXPECT_NEAR(overlap.change.fine, -0.04, 1e-12);
  EXPECT_STREQ(change_resolution(overlap), "below");
  const HistoryBandRow& later = bands.rows[2];
  ASSERT_EQ(later.change.behaviour, Behaviour::monotone);
  EXPECT_NEAR(later.change.observed_order, 2.0, 1e-9);
  EXPECT_NEAR(later.change.band_low, -0.0375 - 1.25 * 0.0375 / 3.0, 1e-12);
  EXPECT_NEAR(later.change.band_high, -0.0375 + 1.25 * 0.0375 / 3.0, 1e-12);
  EXPECT_STREQ(change_resolution(later), "below");
  // A change that its band cannot tell from zero.
  HistoryBandRow unclear = later;
  unclear.change = estimate(0.01, -0.01, 0.005);
  EXPECT_STREQ(change_resolution(unclear), "within band");
  const std::string csv = history_bands_csv(bands);
  EXPECT_NE(csv.find(",0.1,-0.04,-0.04,-0.04,below\n"), std::string::npos) << csv;
}

}  // namespace
}  // namespace needlefem::convergence
