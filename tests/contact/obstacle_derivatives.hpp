// Central differences of an obstacle's gap and normal at a point x: n = ∂g/∂x and G = ∂n/∂x,
// for the needle obstacles' tests. Pick x a distance d off the surface, on one face, so that the
// closest-point piece does not change within the step h = 1 nm (truncation O(h²/d²), <= 1e-7
// relative for d >= 3 µm). `project(x)` returns the ObstacleProjection; G is compared to within
// `tolerance` of max(curvature_scale, |G_ik|).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "physics/contact/rigid_obstacle.hpp"

namespace needlefem::contact {

template <class Project>
void expect_gap_derivatives(const Project& project, const Point3& x, double curvature_scale, double tolerance,
                            const char* what) {
  const double h = 1e-9;
  const ObstacleProjection p = project(x);
  for (int k = 0; k < 3; ++k) {
    Point3 plus = x, minus = x;
    plus[k] += h;
    minus[k] -= h;
    const ObstacleProjection a = project(plus), b = project(minus);
    EXPECT_NEAR((a.gap - b.gap) / (2 * h), p.normal[k], 1e-6) << what << " dg/dx_" << k;
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR((a.normal[i] - b.normal[i]) / (2 * h), p.normal_gradient[3 * i + k],
                  tolerance * std::max(curvature_scale, std::abs(p.normal_gradient[3 * i + k])))
          << what << " dn_" << i << "/dx_" << k;
  }
}

// W = ∂w/∂x by central differences of the obstacle's velocity field at time t (step 0.1 µm).
template <class Obstacle>
void expect_velocity_gradient(const Obstacle& obstacle, const Point3& x, double t) {
  const double h = 1e-7;
  const ObstacleProjection p = obstacle.project(x, t);
  for (int k = 0; k < 3; ++k) {
    Point3 plus = x, minus = x;
    plus[k] += h;
    minus[k] -= h;
    const Point3 wp = obstacle.project(plus, t).velocity, wm = obstacle.project(minus, t).velocity;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR((wp[i] - wm[i]) / (2 * h), p.velocity_gradient[3 * i + k], 1e-9);
  }
}

}  // namespace needlefem::contact
