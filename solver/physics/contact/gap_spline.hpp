// A needle's gap as a C² function: a tricubic B-spline on a regular grid in the needle frame,
// from samples of the exact gap (cad_needle.hpp's distance to a faceted core).
//
// Why: the distance to a triangulated core has a continuous normal but a curvature G that jumps
// between 0 over a facet and 1/d over each facet edge's wedge, with jumps as dense as the facets.
// The penalty's Newton iteration sees those jumps, so whether a CAD tip's run completed depended on
// the facet angle (docs/accuracy.md §9), and each exact query tests hundreds of facets
// (docs/speed.md). The spline is C², costs one 4×4×4 stencil per query, hides facets finer than
// its spacing h, and reproduces the rounded needle to its interpolation error (h⁴ g'''' ≈ 1e-4 ρ
// on an edge of radius ρ) plus the facets' sagitta. h = ρ/6 (cad_needle.cpp): a point's stencil
// reads samples up to 3h away along each axis, and inside the needle the gap has kinks (the core's
// own medial axis) from depth ρ on; 3√3 h < ρ keeps them out of every stencil near the surface.
//
// Coefficients: the cubic quasi-interpolant c_i = (-f_{i-1} + 8 f_i - f_{i+1})/6 along each axis
// (it reproduces cubics, hence the h⁴ error; de Boor, A Practical Guide to Splines, on quasi-
// interpolants), a local rule, so the samples are needed only near the surface: f = clamp(g, -B, B)
// with the band B = kBandCells h, and a node whose coarse neighbour (every fourth node) lies
// farther than B plus their distance from the surface takes ±B without a query (g is 1-Lipschitz).
// The spline equals the unclamped one where every sample in its reach (three nodes each way, 3√3 h)
// is unclamped, i.e. where |g| <= B - 3√3 h; `project` answers only where |s| <= kTrustCells h,
// inside that, and otherwise leaves the point to the exact query.
// Shaft: a needle whose shaft continues behind the rear face (z = 0) is a prism along z there,
// so below the grid's lowest trusted plane (deeper than B + ρ behind the rear face, where every
// closest point within the band lies on the shaft) the spline is read on that plane.
// n = ∇s and G = ∇²s, so the contact's Jacobian is that of its residual (|∇s| = 1 to the
// interpolation error).
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "physics/contact/rigid_obstacle.hpp"

namespace needlefem::contact {

class GapSpline {
 public:
  static constexpr double kBandCells = 8.0;  // B / h
  static constexpr double kTrustCells = 2.5;  // answered where |s| <= this times h (B - 3√3 h - margin)
  static constexpr double kMinNodeLimit = 1e5;

  // Samples `gap` (thread-safe; the exact gap, > 0 outside) on the grid of spacing `spacing` that
  // covers the box [lo, hi] (the tip, rear face on z = 0) grown by the band and the stencil.
  // `prism_below`: the needle is a prism along z behind z = 0 (the shaft), deeper than the band
  // and the edge radius `edge_radius`. Where the grid would hold more than `max_nodes` nodes
  // (8 bytes each) the spacing grows until it does not; max_nodes below kMinNodeLimit is refused
  // (std::invalid_argument): the band and the stencil alone take about 3e4 nodes at any spacing.
  GapSpline(const Point3& lo, const Point3& hi, double spacing, double edge_radius, bool prism_below,
            double max_nodes, const std::function<double(const Point3&)>& gap);

  // g, n and G at ξ (needle frame) where the spline is trusted; nothing elsewhere.
  std::optional<ObstacleProjection> project(const Point3& xi) const;

 private:
  std::size_t index(long i, long j, long k) const {
    return static_cast<std::size_t>(i + n_[0] * (j + n_[1] * k));
  }

  Point3 lo_{};
  double h_ = 0.0, z_floor_ = 0.0;  // z_floor_: the plane read for points deeper along the shaft
  bool prism_below_ = false;
  long n_[3] = {0, 0, 0};
  std::vector<double> coefficient_;
};

}  // namespace needlefem::contact
