// Frictional contact between a tissue boundary surface and a rigid obstacle with a prescribed
// pose: penalty normal traction and Coulomb friction regularised by the slip velocity. Knows the
// obstacle (rigid_obstacle.hpp) and the tissue surface, nothing of the tissue's material: the
// modulus that scales the penalty is given by the caller.
//
// Kinematics, at each quadrature point of each boundary face (TRI6: 6-point degree-4 rule of
// Dunavant 1985; TRI3: the same rule) — never at the nodes, whose weights are wrong (even
// negative-valued shape functions) on quadratic faces:
//   x = Σ N_a (X_a + u_a),  v = Σ N_a u̇_a,  (g, n, G, w, W) = obstacle.project(x, t).
// Normal (penalty, C¹-smoothed at first touch): with the penetration d = ⟨-g⟩,
//   p_N = ε_N d² / (2δ)            for d < δ,
//   p_N = ε_N (d - δ/2)            for d >= δ,
//   ε_N = c μ₀ / h_face,   δ = s h_face / c,   h_face = 2^L √(2 A_face)  (the leg of the right
//   isosceles triangle of the face's reference area, times 2 per mesh.refinement_level L: each
//   level halves the faces near the needle, and the enforcement stays that of level 0, so a
//   refinement study measures the discretisation at one contact law instead of a penalty that
//   doubles with every level and stalls Newton: docs/study.md, "Edge radius and mesh
//   grading"), c = penalty_factor, s = penalty_smoothing,
//   μ₀ the tissue's instantaneous shear modulus. The penalty interpenetration d = p_N h/(c μ₀)
//   (+ δ/2) is then the same fraction of the local element size on every mesh, and the error it
//   causes falls as 1/c (δ too; tests/contact: Hertz indentation at c = 10, 100 and 1000). The
//   smoothing acts below the pressure ε_N δ/2 = s μ₀/2. Why: a needle cavity meshed from the
//   needle starts in touch everywhere, and most of the shaft stays touching at nearly zero
//   pressure; with the plain kink the stiffness of thousands of such points jumps between 0 and
//   ε_N from one Newton iterate to the next (measured: hundreds of points changing state per
//   iteration, IDA_CONV_FAIL with steps cut to 1e-9 s at 2-9 ms on the 0.4 mm brain-tip mesh).
// Augmented enforcement (contact.normal_enforcement = "augmented", the default of cases): the
// penalty law above acts on z = d + o instead of d, where o >= 0 is a per-point multiplier offset
// (λ = ε_N o is the Lagrange multiplier of an augmented Lagrangian, and Uzawa's update
// λ <- <λ + ε_N d> sets o to <z>; Simo & Laursen 1992, Wriggers 2006 §6.3). Uzawa at every
// step would need the step solved again; instead each accepted step (at t_n, the previous one at
// t_{n-1}, h = t_n - t_{n-1}) sets the offset for the next step from the targets z_n = <z(t_n)>:
//   o(t) = <o(t_n) + min(1, (t - t_n)/h) (z_n - o(t_n)) + (t - t_n) (z_n - z_{n-1})/h>,
// the last target extrapolated along its last rate, with what the previous extrapolation missed
// (the penetration d_n = z_n - o(t_n)) ramped in over the first h of the step. Why this form:
//  * o(t) is a known function of time during the step, so Newton sees only ε_N: the stiffness,
//    and the robustness, of the plain penalty;
//  * o is continuous in time (setting o = z_n at once would shift the equilibrium by d at each
//    step, which IDA's error test would read as an error that no step size reduces);
//  * where the pressure varies smoothly the penetration left is the extrapolation's error,
//    ~ h² z̈, instead of p/ε_N; a lagged update without the rate term leaves ~ h ṗ/ε_N, which
//    changes with every change of the step, and the error test then held the steps of a
//    frictional scene near 1.5 ms (docs/accuracy.md, "Contact enforcement").
// Since the pressure is set by z, not by o, a poorly extrapolated offset (at a stick/slip event,
// at first touch) only opens a gap or a penetration of |o - z| for a step, whose force error is
// bounded by the plain penalty's. A point whose target is zero separates, and its offset ramps
// back to zero. The penalty's role is then only to regularise Newton; c = 30-100 give the same
// loads (tests/contact: Hertz indentation by Uzawa's iteration at c = 10 and 100).
// Friction (Coulomb coefficient μ), one of two laws (contact.friction_law):
//
// return-map (default; Wriggers 2006 §5.2.3, Laursen 2002 §5.3, with the elastic-slip stick
// stiffness of Abaqus's penalty friction, Abaqus Analysis User's Guide §37.1.5): each quadrature
// point carries an anchor ξ, a point of the obstacle's body frame where the tissue point is
// elastically tied; a(t) = from_body(ξ, t) is where it is now. With r = x - a, P = I - n nᵀ, the
// elastic slip g_T = P r, ĝ = g_T/|g_T| and x = |g_T|/s₀, s₀ = e h̄ (e = elastic_slip,
// default 0.005 as in Abaqus; h̄ the mean h_face over the contact surface, Abaqus's
// "characteristic contact surface length"), the friction traction is
//   t_T = -μ p_N φ(x) ĝ,
//   φ(x) = x (x <= 1 - b),   x - (x - 1 + b)²/(4b) (|x - 1| < b),   1 (x >= 1 + b),   b = 1,
// i.e. φ(x) = x - x²/4 up to x = 2 and 1 beyond: stick on the tangential stiffness μ p_N / s₀ at
// g_T = 0, falling linearly to zero at |g_T| = 2 s₀, beyond which the point slides at exactly the
// Coulomb limit μ p_N opposite to g_T (the radial return); t_T is continuously differentiable in
// g_T. After each step the integrator accepts (accept_step), a sliding point's anchor is dragged
// along to |g_T| = (1 + b) s₀ (a = x - (1 + b) s₀ ĝ), any other point in contact keeps its
// anchor, and points out of contact re-anchor where they are: the backward-Euler integral of
// Coulomb's rate-independent stick-slip relative to the last accepted state. Effect of the
// regularisation: a sticking point moves at most 2 s₀ (3 µm on 0.3 mm faces) relative to the
// needle; sliding points carry exactly μ p_N.
// Why the blend: with the plain kink t_T = -μ p_N g_T / max(s₀, |g_T|) the Newton matrix jumps
// from μ p_N/s₀ to the slip's, which is singular along ĝ, where a point crosses s₀; Newton's
// updates stop contracting when points cross it between iterates, and IDA cuts the step and
// refactors the matrix. Measured on the Table I tip r = 0.83 mm, 10°, 0.15 mm (level-0 mesh, one
// mesh for all three; docs/accuracy.md §8): the kink took 130 steps, 542 Newton iterations, 57
// convergence failures and 42 factorisations to t = 0.06 s and did not finish; b = 1/2 took
// 182 steps, 767 iterations, 34 failures and 28 factorisations to 0.1 s; b = 1 163, 435, 24 and
// 20. b moved the needle loads and the critical-distance strain and stress by at most 0.04 %, the
// critical-distance strain rate by 16 % (a slip event under way at the last output time).
// Why the stick stiffness scales with p_N and not with ε_N: the stick zone is then s₀ wide at
// every pressure. With ε_T = ε_N it was μ p_N/ε_N, nanometres at the shaft's near-zero
// pressures, below Newton's resolution, and hundreds of points flipped between stick and slip at
// every iterate (measured on the 0.4 mm mesh; with the elastic slip and the smoothing above,
// the Table I tip r = 0.83 mm runs its 0.1 s history at c = 100).
// Why one s₀ for the whole surface, not e h_face per face: the friction law is then the same on
// every mesh of a scene (every mesh.seed, and every refinement level through h_face's 2^L), as
// the normal enforcement is, so a seed or refinement study measures the discretisation alone.
// Per face, the graded mesh's small faces along the needle's edges stuck several times stiffer
// than the shaft's (s₀ 0.21 µm against a mean of 0.75 µm on r = 1.25 mm, 20°, 0.25 mm), where the
// tissue slips over the edge, and IDA cut its steps at their stick/slip changes: one s₀ took
// 208 and 178 steps and 508 and 333 Newton iterations on mesh seeds 1 and 3 where the per-face
// s₀ took 236 and 239 steps and 825 and 682, with the needle loads and the critical-distance
// log strain within 0.1 % (docs/accuracy.md §10, "One elastic slip per contact surface").
// Rate strengthening (contact.rate_strengthening_s_per_m, β; default 2 s/m, 0 in ContactParameters{}):
//   t_T += -β p_N v_T,   v_T = P (v - w)   (v the tissue point's velocity, w the obstacle's there),
// i.e. the friction coefficient of a sliding point is μ + β |v_T| (needle-tissue friction is
// rate-dependent; here the term is a regularisation): +1 % at the 2.6 mm/s of the r = 0.83 mm
// needle's surface at π rad/s. Why: without it the quasi-static stick-slip problem has points
// where the tissue must snap (a patch releasing at once), with no nearby equilibrium: IDA then cuts
// its steps to 1e-13 s at the same rotation (~17°) whatever the speed (measured: the
// r = 0.83 mm, τ = 0.25 mm tips at 0.5, 1 and 2 mm/s stopped at 93-95 % of their histories). The
// viscous term lets the slip run at a finite speed through such an event, and as the steps shrink
// its c_j β p_N P dominates the Newton matrix, which makes the step's problem easier instead of
// harder (with β = 2 s/m the 1 mm/s case runs to the end; docs/accuracy.md §6).
// Newton matrix: ∂t/∂x = -β p_N ∂v_T/∂x + β p' v_T nᵀ, ∂v_T/∂x = -(n·r) G - n (rᵀ G) - P W,
// ∂t/∂v = -β p_N P, r = v - w.
// The Coulomb part does not use y', so its Newton matrix stays bounded as IDA's steps shrink (the velocity
// law's c_j μ p/ε_v does not), which is what lets IDA cut its way through stick/slip transitions.
// Newton matrix (no c_j part), with D = ∂g_T/∂x = P - (n·r) G - n (rᵀ G), s = |g_T|, p' = dp_N/dd:
//   ∂t_T/∂x = μ p' (φ/s) g_T nᵀ - μ p_N [(φ/s) D + (φ'/s₀ - φ/s) ĝ ĝᵀ D]
// (φ/s -> 1/s₀ and the last term -> 0 as g_T -> 0).
//
// velocity (regularised by the slip velocity through y' of IDA; Wriggers 2006 §5.2, Oden &
// Martins 1985):
//   r = v - w,  v_T = (I - n nᵀ) r,  t_T = -μ p_N v_T / √(|v_T|² + ε_v²).
// Effect of the regularisation: |t_T| < μ p_N always, and |t_T| → μ p_N once |v_T| ≫ ε_v
// (|t_T|/(μ p_N) = 1 - ε_v²/(2|v_T|²) + ...: 5e-5 at |v_T| = 100 ε_v). "Sticking" is a viscous
// creep: a point loaded at a fraction φ < 1 of the Coulomb limit slides at
//   |v_T| = ε_v φ / √(1 - φ²),
// so over a time T it slips at most ε_v T φ/√(1-φ²); choose ε_v far below the driving speeds.
// Traction on the tissue t = p_N n + t_T; residual of tissue node a (F = f_int - f_ext):
//   r_a = -∫ N_a t dA₀  (reference area: the penalty and friction act per undeformed area).
// Velocity law's Newton matrix (∂/∂u + c_j ∂/∂u̇), per point, with P = I - n nᵀ, s = √(|v_T|² + ε_v²),
// T = (μ p_N / s)(I - v_T v_Tᵀ / s²):
//   ∂t/∂x = -ε_N n nᵀ + p_N G - T ∂v_T/∂x + μ ε_N (v_T/s) nᵀ,
//   ∂v_T/∂x = -(n·r) G - n (rᵀ G) - P W,        ∂t/∂v = -T P,
// FrictionTangent::consistent (ContactParameters' default) is this exact T. Its stiffness along the slip
// direction, μ p_N ε_v²/s³, vanishes once sliding: there the slip velocity is set by equilibrium
// alone, as in Coulomb's law, and Newton converges quadratically. Two things break it (measured
// in tests/contact/test_frictional_sliding.cpp):
//  * a start that asks loaded points to jump from rest to sliding (a boundary speed switched on
//    at t = 0 with y' = 0): Newton on this arctan-like law from the steep side gains a factor ~1.5
//    in |v_T| per iteration, and smaller steps do not help (the root is the same). Start loads
//    from zero speed (smooth ramps), or from zero pressure;
//  * IDA's corrector tolerance: at a sliding point y' = c_j (y - y_pred) carries the displacement
//    tolerance times c_j; when that reaches ε_v the friction direction flips between iterations
//    and step cuts make it worse (IDA_CONV_FAIL with steps of 1e-20 s). Keep c_j (rtol |u| + atol)
//    ≪ ε_v at the steps the stick/slip transitions need (there: rtol 1e-7, atol 1e-13 for
//    u ~ 50 µm, ε_v = 1e-5 m/s).
// FrictionTangent::secant drops the v_T v_Tᵀ/s² term (stiffness μ p_N/s along the slip): it never
// overshoots, but as a fixed-point iteration in slip it contracts only by A/(A + K V) per
// iteration (A = c_j μ p_N, K the tissue's stiffness, V the slip speed), which tends to 1 as the
// steps shrink: measured, IDA stalls at the onset of slip. The residual, hence the solution, is
// the same for both.
// Which one a velocity-law case uses: contact.friction_tangent, default secant. needlefem runs solve Newton by
// GMRES on the exact Jacobian's action (integration.newton = krylov), so the tangent only
// preconditions, and the secant one measured robust where the consistent one is not (1.5 mm
// brain-tip mesh, 0.01 s: secant 14 steps, 27 Newton iterations, 3 factorisations; consistent
// IDA_CONV_FAIL at t = 9.6 ms). ContactParameters{} keeps the consistent tangent for the tests.
// Why the return map is the default: on the 0.8 mm brain-tip mesh the velocity law stalled IDA
// (steps cut to 1e-8 s) at 1.5 ms with ε_v = 0.1 mm/s and at 34 ms with 0.01 mm/s, whatever the
// tangent: as steps shrink c_j μ p/ε_v dominates the Newton matrix, so cutting does not help.
//   J_ab = -∫ N_a N_b (∂t/∂x + c_j ∂t/∂v) dA₀       (zero where g > 0; with s = 0 touching points,
//   g = 0, contribute ε_N so the first Newton matrix already sees the contact; smoothed, p' = 0 there).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "case/specs/contact_spec.hpp"
#include "model/tet_mesh.hpp"
#include "physics/contact/rigid_obstacle.hpp"
#include "physics/mechanics/surface_load.hpp"

namespace needlefem::contact {

using needlefem::FrictionLaw;
using needlefem::FrictionTangent;
using needlefem::NormalEnforcement;

struct ContactParameters {
  double friction_coefficient = 0.5;
  double penalty_factor = 100.0;              // c in ε_N = c μ₀ / h_face
  double penalty_smoothing = 0.25;            // s in δ = s h_face / c (0: the plain kink)
  double elastic_slip = 0.005;                // e in s₀ = e h̄, h̄ the mean h_face (return map)
  double rate_strengthening = 0.0;            // β, s/m (return map; the case default is 2)
  double reference_modulus = 0.0;             // μ₀, Pa
  // Factor on h_face in ε_N, δ and s₀: 2^mesh.refinement_level, so that refining the mesh near
  // the needle keeps the contact's enforcement of the level-0 mesh (see h_face above).
  double face_size_scale = 1.0;
  double slip_velocity_regularisation = 1e-5; // ε_v, m/s
  FrictionTangent friction_tangent = FrictionTangent::consistent;  // velocity law only
  FrictionLaw friction_law = FrictionLaw::return_map;
  NormalEnforcement normal_enforcement = NormalEnforcement::penalty;
  // Augmented: accepted steps closer than this to the last multiplier update leave the offsets'
  // ramp running (cases: the scene's history, mechanics::history_end, / 1000). Why: the rate (z_n - z_{n-1})/h of the
  // targets carries the Newton error of z divided by h; at the tiny steps of a start or a
  // stick/slip event, extrapolated, it is as large as the error test's tolerance, the test
  // fails, the step shrinks and the rate grows (measured: IDA_CONV_FAIL with steps of 1e-32 s at
  // rtol 1e-8 on the brain-tip scene with an update at every step).
  double multiplier_update_interval = 0.0;  // s
  // Measure each quadrature point's gap from its own gap in the reference configuration at t = 0,
  // g - g(X_q, 0): a surface meshed from the obstacle's shape then starts exactly in touch instead
  // of with the ± interference of its faceted curved faces (micrometres on a 0.4 mm mesh of a
  // 0.5 mm needle, a penalty pressure of ~c μ₀ g/h that would pre-stress the tissue and give IDA
  // an inconsistent start). The offsets shrink with the faces' interpolation error (~h³/R²).
  bool reference_gap_offset = false;
};

// Normal pressure p_N(d) and its slope dp_N/dd at penetration d = -g >= 0 (the smoothed law above;
// smoothing_depth δ = 0 gives the plain penalty).
struct NormalPressure {
  double pressure = 0.0, stiffness = 0.0;
};
NormalPressure normal_pressure(double depth, double penalty, double smoothing_depth);

// The case's [contact] law (parse_contact_spec) in SI units; μ₀ from the caller (the material's
// instantaneous shear modulus), the multiplier update interval from the length of the scene's
// history (mechanics::history_end), and the mesh's mesh.refinement_level (MeshSpec's): the contact
// scales its face sizes by 2^level to keep the level-0 mesh's enforcement.
ContactParameters contact_parameters_from_spec(const ContactSpec& spec, double reference_modulus, double history_end_s,
                                               long mesh_refinement_level);

// Residual and Newton-matrix terms of one face: 3m values and 3m x 3m (row-major), m face nodes.
struct FaceTerms {
  std::vector<double> residual;
  std::vector<double> jacobian;
  Point3 force_on_tissue{};   // ∫ t dA₀
  Point3 moment_on_tissue{};  // ∫ (x - moment_point) × t dA₀
  double contact_area = 0.0;  // reference area where g <= 0
  double slipping_area = 0.0; // of which sliding: |t*| > μ p_N (return map), |v_T| > ε_v (velocity law)
};

// Sum over the surface; the obstacle feels the opposite.
struct ContactResultant {
  Point3 force_on_obstacle{};
  Point3 moment_on_obstacle{};  // about the point given to resultant()
  double contact_area = 0.0;
};

class PenaltyContact final : public mechanics::SurfaceLoad {
 public:
  // `surface` names boundary faces of `mesh` (outward oriented), which must outlive this.
  PenaltyContact(const TetMesh& mesh, const std::string& surface, std::shared_ptr<const RigidObstacle> obstacle,
                 const ContactParameters& parameters);

  std::size_t face_count() const { return faces_.size(); }
  int nodes_per_face() const { return nodes_per_face_; }
  const int* face_nodes(std::size_t face) const { return face_nodes_.data() + face * nodes_per_face_; }
  double penalty(std::size_t face) const { return faces_[face].penalty; }
  // Mean multiplier offset o(t) over the face's quadrature points, m (0 with the plain penalty):
  // a node's pressure is the normal law at its penetration plus this (needle_contact.hpp).
  double mean_offset(std::size_t face, double t) const;
  double elastic_slip() const { return elastic_slip_; }  // s₀, m

  // One face's terms at current positions x (3m) and velocities v (3m) of its nodes.
  // NewtonMatrix::symmetric_preconditioner leaves the friction traction's dependence on the
  // normal gap out of the Jacobian: μ p' ĝ nᵀ (return map; μ p' v_T/s nᵀ for the velocity law)
  // and β p' v_T nᵀ (rate strengthening). Why: they are an unsymmetric coupling of size μ ε_N
  // between the normal and the slip direction, whose stiffness is zero in slip, so the matrix's
  // symmetric part is indefinite as soon as points slide and a Cholesky factor fails (LU
  // instead: 2x the factor and solve time). Without them it stays positive definite (test:
  // tests/contact/test_contact_jacobian.cpp), and GMRES on the exact Jacobian's action makes up
  // the difference: default Table I case 11 Cholesky factorisations instead of 5 + 7 LU,
  // 674 GMRES iterations instead of 726, the same maxima within 0.1 %; but less robust at hard
  // stick/slip events (integration.krylov_preconditioner, whose default is the exact matrix).
  // force_on_tissue, moment_on_tissue and contact_area count only the points whose closest point
  // is on `body` of an articulated obstacle (ObstacleProjection::body; -1: every point).
  FaceTerms face_terms(std::size_t face, const double* x, const double* v, double t, double cj, bool with_jacobian,
                       const Point3& moment_point = {},
                       NewtonMatrix form = NewtonMatrix::exact, int body = -1) const;

  // Of the points on `body` (-1: all).
  ContactResultant resultant(double t, const double* y, const double* ydot, const mechanics::DofMap& dofs,
                             const Point3& moment_point = {}, int body = -1) const;
  // Friction through the slip velocity (the velocity law, or the return map's rate strengthening).
  bool depends_on_rates() const override;

  void add_residual(double t, const double* y, const double* ydot, const mechanics::DofMap& dofs,
                    double* f_u) const override;
  void add_jacobian(double t, const double* y, const double* ydot, double cj, const mechanics::DofMap& dofs,
                    Mat jacobian, NewtonMatrix form) const override;
  // Return map: moves every point's anchor to what the accepted state (t, y) leaves it.
  // Augmented enforcement: starts each point's next multiplier ramp from the accepted penetration.
  void accept_step(double t, const double* y, const double* ydot, const mechanics::DofMap& dofs) override;

 private:
  struct FacePoint {
    std::array<double, 6> shape{};
    double area_weight = 0.0;  // quadrature weight x reference area Jacobian
    double gap_offset = 0.0;   // g(X_q, 0) with reference_gap_offset, else 0
    Point3 anchor{};           // return map: ξ in the obstacle's body frame (X_q at t = 0 to start)
    double offset_start = 0.0;      // augmented: o(t_n), m
    double offset_increment = 0.0;  // augmented: z_n - o(t_n), ramped in over the step, m
    double offset_rate = 0.0;       // augmented: (z_n - z_{n-1}) / h, m/s
    double target = 0.0;            // augmented: z_n, m
  };
  struct Face {
    double penalty = 0.0;
    double smoothing_depth = 0.0;  // δ
    std::vector<FacePoint> points;
  };
  void gather(std::size_t face, const double* y, const double* ydot, const mechanics::DofMap& dofs, double* x,
              double* v) const;
  Point3 point_position(const FacePoint& point, const double* x) const;
  // Multiplier offset o(t) of a point (augmented; 0 with the plain penalty), m.
  double offset(const FacePoint& point, double t) const;
  // Penetration the normal law sees at time t: o(t) - g.
  double effective_depth(const FacePoint& point, double gap, double t) const { return offset(point, t) - gap; }

  const TetMesh& mesh_;
  std::shared_ptr<const RigidObstacle> obstacle_;
  ContactParameters parameters_;
  int nodes_per_face_ = 6;
  std::vector<int> face_nodes_;
  std::vector<Face> faces_;
  double elastic_slip_ = 0.0;  // s₀, m
  double ramp_start_ = 0.0, ramp_duration_ = 0.0, last_update_ = 0.0;  // augmented: the offsets' ramp, s
};

}  // namespace needlefem::contact
