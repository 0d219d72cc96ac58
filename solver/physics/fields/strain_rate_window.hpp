// The strain rate a tissue point sustains over a time window τ, from its deformation gradient at
// the window's two ends:
//
//     d̄_τ(t) = ln λ_max(F_rel) / τ,   F_rel = F(t) F(t - τ)⁻¹,
//
// λ_max the largest principal stretch of the window's relative deformation (the square root of
// the largest eigenvalue of F_rel F_relᵀ). For stretching at a steady rate d along fixed or
// rotating axes it is d (the rigid rotation of the window drops out of the stretch); a burst of
// length Δt ≪ τ at rate r adds about r Δt / τ, the strain it delivers spread over the window.
//
// Why a window: the instantaneous rate D = sym(Ḟ F⁻¹) at one time is set by whatever happens in
// that instant, and under friction the tissue slips in bursts (stick/slip) of a fraction of a
// millisecond whose timing and size change with the mesh (docs/accuracy.md §10). The tissue-level
// data behind the 10 1/s limit tie it to a strain: diffuse axonal injury occurs at strains over
// 10 % and rates over 10 1/s (Rashid, Destrade & Gilchrist 2013, arXiv:1302.4175, summarising the
// animal and human data), i.e. when 10 % strain is delivered within 0.1 / 10 = 10 ms. The default
// window (thresholds.strain_rate_window_s = 0.01 s) judges the rate over that time: a burst
// shorter than it counts by the strain it delivers. It is shorter than the 0.19 strain limit over
// the rate limit (19 ms), so the rate limit does not follow from the strain limit: it fails a
// design that delivers 0.1 of strain within 10 ms, whatever its total strain.
//
// F(t - τ) is interpolated linearly between the two kept snapshots around t - τ; before the first
// snapshot the tissue is taken at rest (F(s) = F(t₀) for s < t₀), as it is before the needle moves.
#pragma once

#include <deque>
#include <vector>

#include "physics/material/tensor.hpp"

namespace needlefem::fields {

class StrainRateWindow {
 public:
  // Snapshots are due `spacing_s` apart (wants_snapshot) and kept as long as the longest window
  // asked for (`longest_window_s`) needs them.
  StrainRateWindow(double longest_window_s, double spacing_s);

  // Whether a snapshot at t is due: the first, or at least spacing_s after the last.
  bool wants_snapshot(double t) const;
  // F per point at time t (after the last snapshot's time); older snapshots the longest window no
  // longer reaches are dropped.
  void add_snapshot(double t, std::vector<material::Mat3d> deformation_gradients);
  // d̄_window per point at the last snapshot's time. window_s > 0, at most the longest window.
  std::vector<double> rate(double window_s) const;

 private:
  struct Snapshot {
    double time;
    std::vector<material::Mat3d> deformation_gradient;
  };
  double longest_window_s_, spacing_s_;
  std::deque<Snapshot> snapshots_;
};

}  // namespace needlefem::fields
