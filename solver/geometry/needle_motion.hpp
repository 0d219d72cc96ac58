// The needle's prescribed motion (paper 001 §II): insertion along +z at speed v and rotation about
// the needle axis at rate ω for t in [0, duration], then rest. Optionally the speeds rise from zero
// over a start ramp t_r with the smoothstep profile s(σ) = σ²(3 - 2σ), σ = t/t_r, so that
//   travel = v τ(t),  angle = ω τ(t),
//   τ(t) = t_r (σ³ - σ⁴/2)          for t < t_r   (τ' = s(σ), τ'' = 6σ(1 - σ)/t_r: both 0 at t = 0),
//   τ(t) = t - t_r/2                for t_r <= t <= duration,   τ(t) = τ(duration) afterwards.
// Why a ramp: a needle switched on at full speed at t = 0 asks IDA for a velocity jump it cannot
// take from a resting tissue (the consistent rates at t = 0 are the needle's, the stored ones
// zero), and with frictional contact Newton must move every loaded point from rest to sliding in
// one step. With the smooth start the consistent initial rates are exactly zero. The cost is the
// travel v t_r/2 the ramp loses (t_r = 0 is the paper's constant-velocity history).
#pragma once

#include "case/specs/motion_spec.hpp"

namespace needlefem {

struct NeedleMotion {
  double insertion_speed = 0.0;  // v, m/s
  double rotation_speed = 0.0;   // ω, rad/s
  double duration = 0.0;         // s
  double ramp = 0.0;             // t_r, s (0 = full speed from t = 0)
  // τ(t): travel / v and angle / ω at time t.
  double elapsed(double t) const;
  // τ'(t): the fraction of the full speeds the needle moves at, 0 outside [0, duration]. The end
  // point counts as moving so that the implicit step landing on t = duration integrates the
  // motion up to it.
  double speed_fraction(double t) const;
};

// The case's motion (parse_motion_spec, which checks it) in SI units.
NeedleMotion needle_motion_from_spec(const MotionSpec& spec);

}  // namespace needlefem
