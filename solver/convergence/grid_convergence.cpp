#include "convergence/grid_convergence.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace needlefem::convergence {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// No order: a band of Fs_osc times half the spread of the three values, centred on f1.
void spread_band(Estimate& e, const Settings& s, Behaviour behaviour, std::string note) {
  e.behaviour = behaviour;
  e.observed_order = e.order = e.extrapolated = kNaN;
  const double spread = std::max({e.coarse, e.medium, e.fine}) - std::min({e.coarse, e.medium, e.fine});
  e.half_width = s.oscillatory_safety_factor * 0.5 * spread;
  e.note = std::move(note);
}
}  // namespace

Estimate estimate(double coarse, double medium, double fine, const Settings& s) {
  Estimate e;
  e.coarse = coarse;
  e.medium = medium;
  e.fine = fine;
  if (!std::isfinite(coarse) || !std::isfinite(medium) || !std::isfinite(fine)) {
    e.observed_order = e.order = e.extrapolated = e.half_width = e.gci_fine = e.band_low = e.band_high = kNaN;
    e.note = "a level has no value";
    return e;
  }
  const double e32 = coarse - medium, e21 = medium - fine;
  const double tolerance = s.mesh_independent_tolerance * std::abs(fine);
  if (std::abs(e21) <= tolerance && std::abs(e32) <= tolerance) {
    e.behaviour = Behaviour::converged;
    e.observed_order = e.order = kNaN;
    e.extrapolated = fine;
    e.half_width = 0.0;
    e.note = "the same on all three meshes (mesh-independent)";
  } else if (e21 * e32 < 0.0) {
    spread_band(e, s, Behaviour::oscillatory,
                fmt::format("oscillatory (R = {:.3g}): band {} x half the spread", e21 / e32, s.oscillatory_safety_factor));
  } else if (std::abs(e21) >= std::abs(e32)) {
    spread_band(e, s, Behaviour::divergent,
                fmt::format("not converging (|f2 - f1| >= |f3 - f2|): band {} x half the spread, which bounds "
                            "the error only where the steps are the meshes' scatter (their spread over mesh.seed)",
                            s.oscillatory_safety_factor));
  } else {
    e.behaviour = Behaviour::monotone;
    e.observed_order = e21 == 0.0 ? std::numeric_limits<double>::infinity()
                                  : std::log(std::abs(e32 / e21)) / std::log(s.ratio);
    e.order = std::min(e.observed_order, s.max_order);
    double safety_factor = s.safety_factor;
    if (e.observed_order > s.max_order)
      e.note = fmt::format("observed order {:.3g} above the formal {:g}: {:g} used", e.observed_order, s.max_order,
                           s.max_order);
    if (e.observed_order < s.min_order) {
      safety_factor = s.oscillatory_safety_factor;
      e.note = fmt::format("observed order {:.3g} < {:g}: not in the asymptotic range, Fs = {:g}", e.observed_order,
                           s.min_order, safety_factor);
    }
    const double rp = std::pow(s.ratio, e.order);
    e.extrapolated = (rp * fine - medium) / (rp - 1.0);
    e.half_width = safety_factor * std::abs(e21) / (rp - 1.0);
    if (e.observed_order >= s.data_range_order) {
      const double data_range = std::abs(coarse - fine);  // monotone: the largest of the three differences
      e.half_width = std::max(e.half_width, safety_factor * data_range);
      e.note += fmt::format("; band {:g} x the data range max - min", safety_factor);
    }
  }
  e.gci_fine = fine != 0.0 ? e.half_width / std::abs(fine) : (e.half_width == 0.0 ? 0.0 : kNaN);
  e.band_low = fine - e.half_width;
  e.band_high = fine + e.half_width;
  return e;
}

Verdict verdict(const Estimate& e, double limit) {
  if (std::isnan(e.band_low) || std::isnan(e.band_high) || std::isnan(limit)) return Verdict::undecided;
  if (e.band_high < limit) return Verdict::pass;
  if (e.band_low > limit) return Verdict::fail;
  return Verdict::undecided;
}

std::string order_text(const Estimate& e) {
  switch (e.behaviour) {
    case Behaviour::converged: return "n/a";
    case Behaviour::monotone: return std::isinf(e.observed_order) ? "inf" : fmt::format("{:.4g}", e.observed_order);
    default: return to_string(e.behaviour);
  }
}

std::string number_text(double x) { return std::isfinite(x) ? fmt::format("{:.9g}", x) : std::string(); }

std::vector<std::string> estimate_cells(const Estimate& e) {
  return {e.behaviour == Behaviour::incomplete ? "" : order_text(e), number_text(e.extrapolated), number_text(e.gci_fine),
          number_text(e.band_low), number_text(e.band_high)};
}

const char* to_string(Behaviour b) {
  switch (b) {
    case Behaviour::converged: return "converged";
    case Behaviour::monotone: return "monotone";
    case Behaviour::oscillatory: return "oscillatory";
    case Behaviour::divergent: return "divergent";
    case Behaviour::incomplete: return "incomplete";
  }
  return "";
}

const char* to_string(Verdict v) {
  switch (v) {
    case Verdict::pass: return "pass";
    case Verdict::fail: return "fail";
    case Verdict::undecided: return "undecided";
  }
  return "";
}

}  // namespace needlefem::convergence
