#include "geometry/needle_tip.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "case/case_error.hpp"

namespace needlefem {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMmPerM = 1e3;
// Relative tolerance under which tau is taken as equal to r (the rounded biopsy tip).
constexpr double kRoundedTolerance = 1e-9;

// 20-point Gauss-Legendre on [a, b]; the integrands here are smooth on each piece.
template <class F>
double gauss_legendre(F f, double a, double b) {
  static const std::array<double, 10> x{0.0765265211334973, 0.2277858511416451, 0.3737060887154195,
                                        0.5108670019508271, 0.6360536807265150, 0.7463319064601508,
                                        0.8391169718222188, 0.9122344282513259, 0.9639719272779138,
                                        0.9931285991850949};
  static const std::array<double, 10> w{0.1527533871307258, 0.1491729864726037, 0.1420961093183820,
                                        0.1316886384491766, 0.1181945319615184, 0.1019301198172404,
                                        0.0832767415767048, 0.0626720483341091, 0.0406014298003869,
                                        0.0176140071391521};
  const double m = 0.5 * (a + b), h = 0.5 * (b - a);
  double sum = 0;
  for (std::size_t i = 0; i < x.size(); ++i) sum += w[i] * (f(m + h * x[i]) + f(m - h * x[i]));
  return sum * h;
}

// Integral over [a, b] of f, split into many panels: the sqrt factor of the chord is
// handled by the substitution x = -r cos(theta) in the caller.
template <class F>
double composite(F f, double a, double b, int panels = 64) {
  double sum = 0, h = (b - a) / panels;
  for (int i = 0; i < panels; ++i) sum += gauss_legendre(f, a + i * h, a + (i + 1) * h);
  return sum;
}

std::string mm(double metres) { return fmt::format("{:.4g} mm", metres * kMmPerM); }

}  // namespace

bool BevelTip::rounded() const { return std::abs(fillet - radius) <= kRoundedTolerance * radius; }

double BevelTip::fillet_centre_x() const { return -radius + fillet; }

double BevelTip::fillet_centre_z() const {
  const double c = std::cos(bevel_rad), s = std::sin(bevel_rad);
  return shaft + (2 * radius * c - fillet * (1 + c)) / s;
}

double BevelTip::fillet_tangent_x() const { return fillet_centre_x() + fillet * std::cos(bevel_rad); }

double BevelTip::length() const {
  if (rounded()) return shaft + radius;
  return fillet_centre_z() + fillet;  // top of the arc; for tau = 0 the sharp tip
}

double BevelTip::profile_top(double x) const { return BevelProfile(*this).top(x); }

BevelProfile::BevelProfile(const BevelTip& tip)
    : radius(tip.radius),
      fillet(tip.fillet),
      shaft(tip.shaft),
      cos_bevel(std::cos(tip.bevel_rad)),
      sin_bevel(std::sin(tip.bevel_rad)),
      tan_bevel(std::tan(tip.bevel_rad)),
      centre_x(tip.fillet_centre_x()),
      centre_z(tip.fillet_centre_z()),
      tangent_x(tip.fillet_tangent_x()) {}

double BevelProfile::top(double x) const {
  if (x >= tangent_x) return shaft + (radius - x) / tan_bevel;
  const double u = x - centre_x;
  return centre_z + std::sqrt(std::max(0.0, fillet * fillet - u * u));
}

double BevelTip::analytic_volume() const {
  if (rounded()) return kPi * radius * radius * shaft + 2.0 / 3.0 * kPi * radius * radius * radius;
  // x = -r cos(theta): dx = r sin(theta) dtheta and the chord 2 sqrt(r^2 - x^2) = 2 r sin(theta),
  // so the integrand 2 r^2 sin^2(theta) h(-r cos(theta)) is smooth except at the tangent point.
  auto integrand = [this](double theta) {
    const double s = std::sin(theta);
    return 2 * radius * radius * s * s * profile_top(-radius * std::cos(theta));
  };
  const double theta_tangent = std::acos(std::clamp(-fillet_tangent_x() / radius, -1.0, 1.0));
  return composite(integrand, 0.0, theta_tangent) + composite(integrand, theta_tangent, kPi);
}

std::vector<RuleViolation> BevelTip::violations() const {
  std::vector<RuleViolation> out;
  if (fillet > radius * (1 + kRoundedTolerance)) {
    out.push_back({"fillet-exceeds-radius",
                   fmt::format("fillet {} is larger than the needle radius {} (fillet = radius is the "
                               "fully rounded tip)", mm(fillet), mm(radius))});
    return out;
  }
  if (rounded()) return out;
  const double tangent_length = fillet / std::tan(bevel_rad / 2);
  const double bevel_length = 2 * radius / std::tan(bevel_rad);
  if (tangent_length > bevel_length)
    out.push_back({"fillet-fits-bevel",
                   fmt::format("the fillet's tangent length tau/tan(alpha/2) = {} exceeds the bevel length "
                               "2r/tan(alpha) = {} (r = {}, alpha = {:.4g} deg, tau = {})",
                               mm(tangent_length), mm(bevel_length), mm(radius), bevel_rad * 180 / kPi, mm(fillet))});
  return out;
}

double CompliantTip::length() const { return shaft + neck_length + head_length; }

double CompliantTip::analytic_volume() const {
  const double a = kPi * radius * radius, neck = kPi * neck_diameter * neck_diameter / 4;
  return a * shaft + neck * neck_length + a * (head_length - point_length) + a * point_length / 3;
}

std::vector<RuleViolation> CompliantTip::violations() const {
  std::vector<RuleViolation> out;
  if (neck_diameter >= 2 * radius)
    out.push_back({"neck-thinner-than-needle",
                   fmt::format("neck diameter {} must be smaller than the needle diameter {}", mm(neck_diameter),
                               mm(2 * radius))});
  if (point_length >= head_length)
    out.push_back({"point-fits-head", fmt::format("conical point {} must be shorter than the head {}",
                                                  mm(point_length), mm(head_length))});
  return out;
}

double NeedleTip::analytic_volume() const {
  if (kind == Kind::Cad) return 0.0;
  return kind == Kind::Bevel ? bevel.analytic_volume() : compliant.analytic_volume();
}

std::vector<RuleViolation> NeedleTip::violations() const {
  if (kind == Kind::Cad) return {};
  return kind == Kind::Bevel ? bevel.violations() : compliant.violations();
}

std::string NeedleTip::describe() const {
  if (kind == Kind::Cad) return fmt::format("CAD tip {}", cad_file);
  if (kind == Kind::Compliant)
    return fmt::format("compliant tip r = {}, neck {} x {}, head {}", mm(compliant.radius),
                       mm(compliant.neck_length), mm(compliant.neck_diameter), mm(compliant.head_length));
  if (bevel.rounded()) return fmt::format("rounded tip r = {}", mm(bevel.radius));
  return fmt::format("bevel tip r = {}, alpha = {:.4g} deg, tau = {}", mm(bevel.radius),
                     bevel.bevel_rad * 180 / kPi, mm(bevel.fillet));
}

NeedleTip needle_tip_from_spec(const NeedleTipSpec& spec) {
  NeedleTip tip;
  const double m = 1.0 / kMmPerM;
  switch (spec.kind) {
    case NeedleKind::cad:
      tip.kind = NeedleTip::Kind::Cad;
      tip.cad_file = spec.cad_file.string();
      break;
    case NeedleKind::compliant:
      tip.kind = NeedleTip::Kind::Compliant;
      tip.compliant = {spec.radius_mm * m,      spec.shaft_mm * m,         spec.neck_length_mm * m,
                       spec.neck_diameter_mm * m, spec.head_length_mm * m, spec.point_length_mm * m};
      break;
    case NeedleKind::bevel:
      tip.bevel = {spec.radius_mm * m, spec.bevel_deg * kPi / 180, spec.fillet_mm * m, spec.shaft_mm * m};
      break;
  }
  return tip;
}

std::vector<RuleViolation> brain_tip_scene_violations(const TissueCubeSpec& tissue, const NeedleTip& tip) {
  std::vector<RuleViolation> out = tip.violations();
  const double edge = tissue.cube_edge_mm / kMmPerM;
  const double core = tissue.core_width_mm / kMmPerM;
  const double core_element = tissue.core_element_mm / kMmPerM;
  if (tissue.core_element_mm > tissue.outer_element_mm)
    out.push_back({"core-finer-than-outside",
                   fmt::format("core element size {} exceeds the outer element size {}", mm(core_element),
                               mm(tissue.outer_element_mm / kMmPerM)),
                   "tissue.core_element_mm"});
  if (core >= edge)
    out.push_back({"core-inside-cube",
                   fmt::format("core width {} must be smaller than the cube edge {}", mm(core), mm(edge)),
                   "tissue.core_width_mm"});
  if (tip.kind == NeedleTip::Kind::Cad) return out;  // its rules: mesh/cad_tip.hpp, once gmsh has read it
  if (tip.radius() >= core / 2)
    out.push_back({"core-contains-needle", fmt::format("needle radius {} must be smaller than half the core "
                                                       "width ({})", mm(tip.radius()), mm(core / 2))});
  // At least one core element of tissue must remain ahead of the tip.
  if (out.empty() && tip.length() + core_element > edge)
    out.push_back({"tip-fits-cube",
                   fmt::format("the tip is {} long; with one core element ({}) ahead of it it does not fit "
                               "the {} cube", mm(tip.length()), mm(core_element), mm(edge))});
  return out;
}

void require_valid_brain_tip_scene(const NeedleTipSpec& tip, const TissueCubeSpec& tissue) {
  const auto violations = brain_tip_scene_violations(tissue, needle_tip_from_spec(tip));
  if (violations.empty()) return;
  std::string reasons;
  for (const auto& v : violations) reasons += fmt::format("{}rule '{}': {}", reasons.empty() ? "" : "; ", v.rule, v.message);
  // Under the key of the first rule broken (a tissue rule names its tissue key, not `needle`).
  throw case_error(tip.origin, violations.front().key, "impossible geometry: " + reasons);
}

}  // namespace needlefem
