// Rigid obstacles the tissue surface can touch, described by what contact needs at a point x
// of the deformed tissue surface (Wriggers, Computational Contact Mechanics, 2006, §4.1):
//   g(x)      signed gap: distance from x to the obstacle surface, > 0 outside, < 0 inside;
//   n(x)      unit outward normal of the obstacle at the closest point (n = ∂g/∂x);
//   G(x)      ∂n/∂x (curvature: 0 for a plane, (I - n nᵀ)/|x - c| for a sphere of centre c);
//   w(x)      velocity of the obstacle's material point at the closest point;
//   W(x)      ∂w/∂x (0 for a translating obstacle);
// and the rigid motion itself, for friction anchors that ride with the obstacle: the body-frame
// coordinates ξ of a spatial point at time t and back (to_body(from_body(ξ, t), t) = ξ).
// Poses are prescribed functions of time: a plane through p(t) = p0 + v t with fixed normal,
// a sphere with centre c(t) = c0 + v t (Hertz indentation tests), or another obstacle shifted by
// a fixed offset.
#pragma once

#include <array>
#include <memory>

#include "model/tet_mesh.hpp"

namespace needlefem::contact {

using Matrix3 = std::array<double, 9>;  // row-major

struct ObstacleProjection {
  double gap = 0.0;
  Point3 normal{};
  Matrix3 normal_gradient{};
  Point3 velocity{};
  Matrix3 velocity_gradient{};
  int body = 0;  // which rigid body of an articulated obstacle the closest point is on (hinged_needle.hpp)
};

class RigidObstacle {
 public:
  virtual ~RigidObstacle() = default;
  virtual ObstacleProjection project(const Point3& x, double t) const = 0;
  virtual Point3 to_body(const Point3& x, double t) const = 0;
  virtual Point3 from_body(const Point3& xi, double t) const = 0;
};

// Body frame = scene frame translated by v t (the translating obstacles below).
class TranslatingObstacle : public RigidObstacle {
 public:
  explicit TranslatingObstacle(const Point3& velocity) : velocity_(velocity) {}
  Point3 to_body(const Point3& x, double t) const override;
  Point3 from_body(const Point3& xi, double t) const override;

 protected:
  Point3 velocity_;
};

// The half-space {(x - p(t))·n < 0} is solid; n is normalised on construction.
class TranslatingPlane final : public TranslatingObstacle {
 public:
  TranslatingPlane(const Point3& point, const Point3& normal, const Point3& velocity);
  ObstacleProjection project(const Point3& x, double t) const override;

 private:
  Point3 point_, normal_;
};

// A solid ball of radius R whose centre moves as c0 + v t.
class TranslatingSphere final : public TranslatingObstacle {
 public:
  TranslatingSphere(const Point3& centre, double radius, const Point3& velocity);
  ObstacleProjection project(const Point3& x, double t) const override;

 private:
  Point3 centre_;
  double radius_;
};

// Another obstacle moved by a fixed offset c: g, n, G, w, W at x are the other's at x - c, and
// its body frame is shifted by c (a needle placed by the case: scene_obstacle.hpp).
class OffsetObstacle final : public RigidObstacle {
 public:
  OffsetObstacle(std::shared_ptr<const RigidObstacle> obstacle, const Point3& offset);
  ObstacleProjection project(const Point3& x, double t) const override;
  Point3 to_body(const Point3& x, double t) const override;
  Point3 from_body(const Point3& xi, double t) const override;

 private:
  Point3 shifted(const Point3& x) const { return {x[0] - offset_[0], x[1] - offset_[1], x[2] - offset_[2]}; }
  std::shared_ptr<const RigidObstacle> obstacle_;
  Point3 offset_;
};

}  // namespace needlefem::contact
