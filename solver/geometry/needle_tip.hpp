// Needle-tip shapes of the two papers, in metres, with the needle axis along +z and the
// rear face of the tip in the plane z = 0 (flush with the tissue's entry face).
//
// Bevel tip (paper 001, Fig. 1): cylinder of radius r; bevel plane at angle alpha to the axis,
// heel at (x = +r, z = shaft), sharp tip on the opposite generator x = -r at
// z = shaft + 2r/tan(alpha). The sharp tip is rounded in the side profile (x-z plane) by an
// arc of radius tau tangent to the bevel line and to the generator x = -r; the profile is
// extruded across y and intersected with the cylinder. Arc centre:
//   x_c = -r + tau,  z_c = shaft + (2r cos(alpha) - tau (1 + cos(alpha))) / sin(alpha),
// tangent length from the sharp tip along either line = tau / tan(alpha/2).
// tau = r is the fully rounded biopsy tip: a hemisphere on the shaft (alpha does not apply).
//
// Compliant tip (paper 000, Fig. 2b): shaft (radius r), neck (diameter d, length l),
// magnetised head (radius r, length L) whose last point_length is a cone.
#pragma once

#include <string>
#include <vector>

#include "case/specs/needle_tip_spec.hpp"

namespace needlefem {

// A violated geometric validity rule: its stable name, a sentence with the numbers, and the case
// key (or table) the rule is about, under which an error reports it.
struct RuleViolation {
  std::string rule;
  std::string message;
  std::string key = "needle";
};

struct BevelTip {
  double radius = 0, bevel_rad = 0, fillet = 0, shaft = 0;

  bool rounded() const;   // tau == r: hemispherical end
  double length() const;  // axial extent from the rear face to the foremost point
  // Height of the side profile above the rear face at lateral position x in [-r, r]
  // (not used for the rounded tip, whose top also depends on y).
  double profile_top(double x) const;
  double fillet_centre_x() const;
  double fillet_centre_z() const;
  double fillet_tangent_x() const;  // x of the arc's tangent point on the bevel line
  // Volume by an independent route: the rounded tip in closed form; the bevel tip as
  // the integral of the profile height over the disk, V = int_{-r}^{r} 2 sqrt(r^2-x^2) h(x) dx,
  // evaluated with Gauss-Legendre on pieces split at the profile's kinks (x = x_tangent).
  double analytic_volume() const;
  std::vector<RuleViolation> violations() const;
};

// A bevel tip's side profile with the bevel angle's trigonometry evaluated once, for code that
// asks for the profile at every contact quadrature point of every residual (the needle obstacle).
// The same numbers as BevelTip's functions.
struct BevelProfile {
  BevelProfile() = default;  // no tip: every number 0
  explicit BevelProfile(const BevelTip& tip);
  double top(double x) const;  // BevelTip::profile_top

  double radius = 0, fillet = 0, shaft = 0;
  double cos_bevel = 0, sin_bevel = 0, tan_bevel = 0;
  double centre_x = 0, centre_z = 0, tangent_x = 0;  // fillet_centre_x, fillet_centre_z, fillet_tangent_x
};

struct CompliantTip {
  double radius = 0, shaft = 0, neck_length = 0, neck_diameter = 0, head_length = 0, point_length = 0;
  double length() const;
  double analytic_volume() const;
  std::vector<RuleViolation> violations() const;
};

// The needle described by a case ([needle] table), tagged by kind. A CAD tip (needle.cad_file)
// is known only once gmsh has read it (mesh/cad_tip.hpp, which checks its rules): here its
// radius, length and volume are 0 and it has no rules of its own.
struct NeedleTip {
  enum class Kind { Bevel, Compliant, Cad } kind = Kind::Bevel;
  BevelTip bevel;
  CompliantTip compliant;
  std::string cad_file;
  double radius() const { return kind == Kind::Bevel ? bevel.radius : kind == Kind::Compliant ? compliant.radius : 0.0; }
  double length() const {
    return kind == Kind::Bevel ? bevel.length() : kind == Kind::Compliant ? compliant.length() : 0.0;
  }
  double analytic_volume() const;
  std::vector<RuleViolation> violations() const;
  std::string describe() const;
};

// The case's tip (parse_needle_tip_spec) in SI units.
NeedleTip needle_tip_from_spec(const NeedleTipSpec& spec);

// Rules of the brain-tip scene as a whole: the tip against the cube and its refined core.
std::vector<RuleViolation> brain_tip_scene_violations(const TissueCubeSpec& tissue, const NeedleTip& tip);

// Throws CaseError (the tip spec's origin) listing every violated rule of the brain-tip scene of
// `tip` in `tissue`, under the key of the first rule broken.
void require_valid_brain_tip_scene(const NeedleTipSpec& tip, const TissueCubeSpec& tissue);

}  // namespace needlefem
