// The rigid bevel needle of paper 001 as a contact obstacle (rigid_obstacle.hpp): signed
// distance g, normal n = ∂g/∂x, its gradient G = ∂n/∂x, and the needle's rigid velocity field.
//
// Shape (needle frame, geometry/needle_tip.hpp): the solid needle is C = A ∩ B with
//   A = {ξ² + η² <= r²}                      (the cylinder; the shaft continues behind z = 0),
//   B = {(ξ, ζ) in P} x (all η)              (the side profile P extruded across y),
// P = {ξ >= -r, ζ <= h(ξ)}: below the bevel line and the fillet arc of radius τ, right of the
// generator ξ = -r. P is the Minkowski sum of the wedge W' (apex at the fillet centre c,
// bounded by the bevel line and the generator both moved inwards by τ; opening angle α) and a
// disc of radius τ, so its signed distance is exact everywhere as sd_P = sd_W' - τ: the bevel
// plane (G = 0), the fillet cylinder around c (2-D normal (q - c)/|q - c|, G = (I - n nᵀ)/|q - c|
// in the x-z block) or the generator plane (G = 0). The rounded tip (τ = r) is the capsule
// "ray {ξ = η = 0, ζ <= shaft} ⊕ ball(r)": g = |x - p| - r with p the closest point of the ray,
// G = (I - n nᵀ - [ζ < shaft] e_z e_zᵀ)/|x - p|.
// Edges: the bevel-cylinder and fillet-cylinder edges are rounded with their physical radius
// ρ = min(τ, needle.edge_radius_um) (default 100 µm; a ground needle's edge is a few to some tens
// of µm, but 50 µm stalled the contact Newton iteration of the default tip on the graded mesh;
// the scene mesher grades the mesh to resolve ρ): the needle is the core C_ρ ⊕ ball(ρ), C_ρ the tip with every face moved inwards
// by ρ (radius r - ρ, fillet τ - ρ, same fillet centre, bevel line moved by ρ), so
//   g = g_core - ρ,  n and G those of the core at distance g + ρ.
// Why: inside a sharp edge the nearest face switches across the edge's bisector, and the normal,
// hence the penalty traction p n, jumps there; a residual that jumps stalls Newton at any step
// size (measured: IDA_CONV_FAIL with h -> 1e-14 on the 0.8 mm mesh at 0.9 ms). With the rounding
// the normal is continuous for every point shallower than ρ. Points are deeper than the penalty
// penetration (~p h/(c μ₀)) alone: faceted cavity faces start up to ~10 µm inside the needle on
// a 0.8 mm mesh (reference_gap_offset hides the interference from the gap, not from the
// projection). Both shrink with the element size at the edge, which is why the rounding needs the
// graded mesh: on paper 001's uniform 0.4 mm core a radius of r/10 (32 µm for r = 0.32 mm) left 8
// of 24 designs stopping with IDA_CONV_FAIL and r/4 was needed (the former contact.edge_rounding). The mesher carves
// the cavity from the sharp tip, which is larger along the edges by ρ(1/sin(θ/2) - 1) at an edge
// of dihedral angle θ; the run moves the cavity's nodes onto this rounded needle
// (model/cavity_rounding.hpp), so the tissue has no re-entrant edge either.
// Both A and B are convex, hence so is C, and the closest point is unique outside C:
//   inside (sd_A <= 0 and sd_B <= 0): g = max(sd_A, sd_B), exact (the nearest boundary point is
//     on the nearer of the two surfaces), with that surface's n and G. The normal jumps across the
//     bisector of the bevel-cylinder edge; penetrations are a small fraction of the element size
//     (penalty_contact.hpp), so only points within that distance of the edge can see the jump.
//   outside: the projection onto A if it lies in B (g = sd_A), else the projection onto B if it
//     lies in A (g = sd_B), else the closest point p of the edge curve ∂A ∩ ∂B,
//       c(θ) = (r cos θ, r sin θ, h(r cos θ)),  θ in [-π, π],
//     found by sampling, golden-section search and a Newton polish of (x - c)·c' = 0; g = |x - p|, n = (x - p)/g and
//       G = (I - n nᵀ - c' c'ᵀ / (|c'|² - (x - c)·c'')) / g      (differentiate (x - c(θ))·c'(θ) = 0),
//     except at θ = ±π (the fillet's foremost-left point, where the two edge branches meet at a
//     kink and the closest point stays put): G = (I - n nᵀ)/g. The penalty acts only where g <= 0,
//     so the edge branch gives exact gaps (the initial-gap check) and the sign, never forces.
// Pose (the needle frame coincides with the scene frame at t = 0; axis z through the centre of
// the entry face, rear face of the tip at z = 0): with τ(t) of the motion (geometry/needle_motion.hpp,
// τ = t for the paper's constant speeds),
//   x = R_z(ω τ) ξ + v τ e_z;    reference point (centre of the rear face) = v τ e_z.
// Rigid velocity field, evaluated at the tissue point x itself (the needle material point that
// coincides with x; at active points |x - p| is the penalty penetration, a fraction of h):
//   w(x) = τ'(t) (v e_z + ω e_z × (x - v τ e_z)),   W = ∂w/∂x = τ'(t) ω [e_z]×,
// both zero for t > duration (the needle stops).
#pragma once

#include <memory>
#include <vector>

#include "geometry/needle_motion.hpp"
#include "geometry/needle_tip.hpp"
#include "physics/contact/rigid_obstacle.hpp"

namespace needlefem {
class Case;
}

namespace needlefem::contact {

// A needle shape other than the analytic bevel (a CAD tip: cad_needle.hpp), in the needle frame.
class NeedleShape {
 public:
  virtual ~NeedleShape() = default;
  virtual ObstacleProjection project(const Point3& xi) const = 0;  // g, n, G (no velocity)
  virtual double edge_radius() const = 0;
};

// What the cavity's contact and its outputs need of a needle of the brain-tip scene: the rigid
// bevel or CAD tip below, or the hinged compliant tip (hinged_needle.hpp).
class Needle : public RigidObstacle {
 public:
  virtual Point3 rear_face_centre(double t) const = 0;
  virtual const NeedleMotion& motion() const = 0;
  virtual double edge_radius() const = 0;
};

class RigidNeedle final : public Needle {
 public:
  // edge_radius = ρ in metres before the cap ρ <= τ (case key needle.edge_radius_um). Throws
  // std::invalid_argument for tips that break their validity rules and for ρ <= 0.
  RigidNeedle(const BevelTip& tip, const NeedleMotion& motion, double edge_radius);
  // Any other shape, moved by the same motion and pose.
  RigidNeedle(std::shared_ptr<const NeedleShape> shape, const NeedleMotion& motion);

  ObstacleProjection project(const Point3& x, double t) const override;
  // Gap, normal and normal gradient in the needle frame (no velocity).
  ObstacleProjection project_in_needle_frame(const Point3& xi) const;
  // Where the needle point that sat at ξ at t = 0 is at time t, and its inverse.
  Point3 from_body(const Point3& xi, double t) const override;
  Point3 to_body(const Point3& x, double t) const override;
  Point3 rear_face_centre(double t) const override;
  const NeedleMotion& motion() const override { return motion_; }
  double edge_radius() const override { return edge_radius_; }

 private:
  // The rigid motion at one time: rotation R_z (cos, sin) and the rear-face centre d, computed
  // once per projection (the contact search calls project() at every quadrature point).
  struct Pose {
    double c = 1.0, s = 0.0;
    Point3 d{};
    Point3 from_body(const Point3& xi) const;
    Point3 to_body(const Point3& x) const;
  };
  Pose pose(double t) const;
  ObstacleProjection project_rounded(const Point3& xi) const;
  ObstacleProjection project_bevel(const Point3& xi) const;
  ObstacleProjection project_on_edge(const Point3& xi) const;

  BevelTip tip_;
  BevelProfile core_;               // the tip with every face moved inwards by the edge radius
  std::vector<Point3> edge_samples_;  // the core's edge curve at edge_sample_angle(k), k = 0..kEdgeSamples
  std::shared_ptr<const NeedleShape> shape_;  // null: the bevel tip_
  NeedleMotion motion_;
  double edge_radius_ = 0.0;
};

}  // namespace needlefem::contact
