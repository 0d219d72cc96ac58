// Paper 000's compliant needle (geometry/needle_tip.hpp's CompliantTip) as a contact obstacle:
// two rigid bodies joined at the pseudo-rigid-body pivot (steering/hinge.hpp), the centre of the
// neck, the head turned about it by a prescribed tilt (the run finds the tilt from the hinge's
// moment balance: run/hinge_coupling.hpp).
//   stem  the shaft (radius r, z <= s, continuing behind the entry face) and the neck's rear half
//         (radius d/2, s <= z <= s + l/2);
//   head  the neck's front half (s + l/2 <= z <= s + l) and the magnetised head: radius r from
//         z = s + l to s + l + L - p, then a cone of length p to a point on the axis.
// Each body is a union of convex solids of revolution. A solid's meridian section (R, z) is a
// convex polygon P symmetric about R = 0, so the closest point of x (R = √(x² + y²)) lies in x's
// meridian half-plane and, with q = (R, z),
//   g = sd_P(q),   n = n_R e_R + n_z e_z,
//   G = H_RR e_R e_Rᵀ + H_Rz (e_R e_zᵀ + e_z e_Rᵀ) + H_zz e_z e_zᵀ + (n_R/R)(I - e_R e_Rᵀ - e_z e_zᵀ),
// the last term the hoop curvature, H the 2-D Hessian of sd_P: zero inside P and facing an edge,
// (I - n nᵀ)/|q - c| outside a vertex c (n = (q - c)/|q - c|). Inside P, sd_P is the largest
// signed distance to the edges' lines (exact for a convex polygon). Edges are rounded as the
// bevel's (needle_obstacle.hpp): P = P_ρ ⊕ disc(ρ), P_ρ the polygon with every edge moved inwards
// by ρ, so sd_P = sd_{P_ρ} - ρ, and the normal is continuous for every point shallower than ρ.
// ρ = min(needle.edge_radius_um, a quarter of the solid's radius): the neck (d/2 = 0.1 mm) is
// thinner than the 100 µm default.
// A body's gap is the smallest of its solids' (exact outside their union; inside, contact points
// sit a penalty penetration deep), the needle's the smaller of the two bodies', and the projection
// names the body (ObstacleProjection::body: 0 stem, 1 head). The concave corners where the neck
// meets the shaft and the head stay sharp: a tissue point there sees the normal switch between
// solids across the corner's bisector (as at a CAD tip's concave edges, cad_needle.hpp).
//
// Pose. The stem moves as the rigid bevel needle does (needle_motion.hpp, τ = τ(t)):
//   x = Q_s ξ + d_s,   Q_s = R_z(ω τ),   d_s = v τ e_z;
// the head is turned besides about the pivot p = (0, 0, s + l/2) by the tilt θ(t) = (θ_x, θ_y, 0),
// a rotation vector normal to the shaft (its length the turning angle; a tilt towards the unit
// pull direction e of the x-y plane is angle · e_z × e), R_h = exp([θ]×):
//   x = R_h Q_s ξ + d_s + p - R_h p.
// Velocity of the body point at x: w = ḋ + Ω × (x - d) with Ω_s = τ' ω e_z, ḋ_s = τ' v e_z, and for
// the head Ω_h = Ω_R + R_h Ω_s, Ω_R = J(θ) θ̇ (the left Jacobian of SO(3),
// J = I + (1 - cos a)/a² [θ]× + (a - sin a)/a³ [θ]×², a = |θ|), ḋ_h = ḋ_s - Ω_R × (R_h p);
// W = ∂w/∂x = [Ω]×.
// Friction anchors (penalty_contact.hpp) live in one body frame, the needle at t = 0: a body-frame
// point ξ belongs to the head when ξ_z > p_z. to_body(x) maps x back by the head's pose when that
// lands on the head's side, by the stem's otherwise.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "geometry/needle_tip.hpp"
#include "physics/contact/needle_obstacle.hpp"

namespace needlefem::contact {

// A convex solid of revolution about the z axis, edges rounded by ρ.
class RevolvedSolid {
 public:
  // `meridian`: the polygon's vertices (R >= 0, z) counter-clockwise in the (R, z) plane, from
  // (0, z_rear) round to (0, z_front); the mirror half R < 0 is implied. Throws
  // std::invalid_argument when ρ is negative or eats an edge of the polygon.
  RevolvedSolid(const std::vector<std::array<double, 2>>& meridian, double edge_radius);
  ObstacleProjection project(const Point3& xi) const;  // g, n, G (no velocity)

 private:
  std::vector<std::array<double, 2>> core_;  // the full polygon P_ρ, counter-clockwise
  double edge_radius_ = 0.0;
};

// The head's tilt against time: rotation vectors θ_i = (θ_x, θ_y) at times t_i (strictly
// increasing), linear in between, held beyond the ends; no samples = no tilt.
class HeadTilt {
 public:
  HeadTilt() = default;
  HeadTilt(std::vector<double> times, std::vector<std::array<double, 2>> tilt);
  std::array<double, 2> at(double t) const;
  std::array<double, 2> rate(double t) const;  // of the segment containing t (right-hand at a sample)
  const std::vector<double>& times() const { return times_; }
  const std::vector<std::array<double, 2>>& samples() const { return tilt_; }

 private:
  std::vector<double> times_;
  std::vector<std::array<double, 2>> tilt_;
};

class HingedNeedle final : public Needle {
 public:
  enum Body { stem = 0, head = 1 };
  // Throws std::invalid_argument for a tip that breaks its rules and for ρ <= 0.
  HingedNeedle(const CompliantTip& tip, const NeedleMotion& motion, double edge_radius,
               std::shared_ptr<const HeadTilt> tilt);

  ObstacleProjection project(const Point3& x, double t) const override;
  Point3 from_body(const Point3& xi, double t) const override;
  Point3 to_body(const Point3& x, double t) const override;
  Point3 rear_face_centre(double t) const override;
  const NeedleMotion& motion() const override { return motion_; }
  double edge_radius() const override { return edge_radius_; }

  // Gap, normal and its gradient of one body in the body frame.
  ObstacleProjection project_body(Body body, const Point3& xi) const;
  Point3 pivot(double t) const;           // where the pivot is at time t
  Point3 head_axis(double t) const;       // the head's direction (unit), e_z untilted
  const HeadTilt& tilt() const { return *tilt_; }
  double pivot_height() const { return pivot_z_; }  // p_z in the body frame, m

 private:
  struct Pose {  // x = Q ξ + d, velocity ḋ + Ω × (x - d)
    Matrix3 Q{};
    Point3 d{}, d_rate{}, spin{};
    Point3 from_body(const Point3& xi) const;
    Point3 to_body(const Point3& x) const;
  };
  Pose stem_pose(double t) const;
  Pose head_pose(double t) const;

  std::vector<RevolvedSolid> stem_, head_;
  NeedleMotion motion_;
  double edge_radius_ = 0.0, pivot_z_ = 0.0;
  std::shared_ptr<const HeadTilt> tilt_;
};

}  // namespace needlefem::contact
