// A rigid needle tip from CAD (needle.kind = "cad"): the closed triangulation of the CAD solid
// (mesh/cad_tip.hpp, facets of needle.cad_facet_um and needle.cad_facet_deg), needle frame, axis +z, rear face on z = 0.
//
// Edge rounding, the same construction as the analytic bevel (needle_obstacle.hpp): the needle
// is the core C_ρ ⊕ ball(ρ), C_ρ the tip with every face moved inwards by ρ, so
//   g(ξ) = sd(ξ, ∂C_ρ) - ρ,  n = ∇g,  G = ∂n/∂ξ,
// with sd the signed distance to the core's triangulation (triangle_surface.hpp). Outside the
// core (every point shallower than ρ inside the needle) n = (ξ - p)/|ξ - p| with p the closest
// point of the core: continuous, since the distance to a closed set is C¹ off the set and off its
// outer medial axis (which concave corners of the core have; convex edges have none). G is that
// of the distance to the closest feature: 0 on a facet, (I - n nᵀ - t tᵀ)/d on a facet edge of
// tangent t, (I - n nᵀ)/d at a vertex (negated inside the core, where n = (p - ξ)/d).
// The core's triangulation: each vertex v moved to v - ρ m, m the least-squares solution of
// m·n_f = 1 over the faces f around v (angle-weighted), through the pseudo-inverse of
// Σ θ_f n_f n_fᵀ with eigenvalues below 1e-2 of the largest dropped. Where at most three distinct
// planes meet (a facet, a sharp edge between two faces, a corner of three), that is the vertex of
// the inner parallel body exactly (its faces at distance ρ from the tip's); on a smooth curved
// face the normals around v differ by the facet angle and m is the mean normal (the dropped
// directions hold a normal spread below ~11°, where the exact offset differs by < 0.005 ρ).
// Moved faces run on past the core's edges (a face loses a strip ρ tan(θ/2) wide along an edge
// whose normals differ by θ, five facets of 20 µm for ρ = 0.1 mm at 90°), so the moved
// triangulation is trimmed to {y : d(y, tip) >= ρ}: triangles cut where that changes, the cut
// found by bisection on d. (OpenCASCADE's own offset, occ::addThickSolid, returned only a stub of
// the bevel tip's inner wall: measured on the exported paper tip.) The trimmed core is open
// along its edges, so inside/outside comes from the tip's surface where the core's pseudo-normal
// is incomplete: inside the core iff sd(ξ, tip) < -ρ.
// Rear face: the facets on z = 0 are removed and the rim extruded backwards by
// kShaftExtension as a tube: the shaft continues behind the entry face (as the analytic
// cylinder does), so the core is not rounded at the rim where the tissue's entry face meets it.
// The contact reads the gap through a C² spline of these exact values (gap_spline.hpp) on a grid
// of ρ/6, so neither its Newton iteration nor its cost sees facets finer than that grid; the exact
// projection answers where the spline does not (farther than its band from the surface).
// Limits: concave edges of the tip (the inner corners of a side port) stay sharp (the closing of
// the complement is not built), so a tissue point just outside such a corner sees the normal turn
// across the corner's bisector; a feature thinner than 2ρ leaves no core there: it is rounded away.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "physics/contact/gap_spline.hpp"
#include "physics/contact/needle_obstacle.hpp"
#include "physics/contact/triangle_surface.hpp"

namespace needlefem::contact {

class CadNeedleShape final : public NeedleShape {
 public:
  // `tip`: the closed triangulation of the tip (metres). Throws std::invalid_argument when it is
  // not closed, has no facets on z = 0 facing -z, or nothing is left of it inside by ρ.
  CadNeedleShape(TriangleSoup tip, double edge_radius);

  // Through the gap spline (gap_spline.hpp) within its band, else project_exact.
  ObstacleProjection project(const Point3& xi) const override;
  // From the core's triangulation (the equations above).
  ObstacleProjection project_exact(const Point3& xi) const;
  double edge_radius() const override { return edge_radius_; }
  double tip_volume() const { return tip_volume_; }  // of the triangulation, m³
  const TriangleSurface& core() const { return *core_; }

 private:
  // The core's triangulation: `offset` (the tip's vertices moved inwards by ρ) trimmed to
  // {y : d(y, tip) >= ρ}; sets core_ and sign_reliable_.
  void trim_core(const TriangleSoup& tip, TriangleSoup offset, const std::vector<Point3>& facet_normal);

  double edge_radius_ = 0.0, tip_volume_ = 0.0, scale_ = 0.0;
  std::unique_ptr<TriangleSurface> surface_;  // the tip's, rear face opened into the shaft tube
  std::unique_ptr<TriangleSurface> core_;     // the core's
  std::vector<char> sign_reliable_;           // per core triangle: its pseudo-normals are whole
  std::unique_ptr<GapSpline> spline_;
};

}  // namespace needlefem::contact
