// Equations: rigid_obstacle.hpp.
#include "physics/contact/rigid_obstacle.hpp"

#include <cmath>
#include <stdexcept>

namespace needlefem::contact {

namespace {

double norm(const Point3& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

}  // namespace

Point3 TranslatingObstacle::to_body(const Point3& x, double t) const {
  return {x[0] - velocity_[0] * t, x[1] - velocity_[1] * t, x[2] - velocity_[2] * t};
}

Point3 TranslatingObstacle::from_body(const Point3& xi, double t) const {
  return {xi[0] + velocity_[0] * t, xi[1] + velocity_[1] * t, xi[2] + velocity_[2] * t};
}

TranslatingPlane::TranslatingPlane(const Point3& point, const Point3& normal, const Point3& velocity)
    : TranslatingObstacle(velocity), point_(point) {
  const double length = norm(normal);
  if (!(length > 0.0)) throw std::invalid_argument("TranslatingPlane: zero normal");
  for (int i = 0; i < 3; ++i) normal_[i] = normal[i] / length;
}

ObstacleProjection TranslatingPlane::project(const Point3& x, double t) const {
  ObstacleProjection p;
  for (int i = 0; i < 3; ++i) p.gap += (x[i] - point_[i] - velocity_[i] * t) * normal_[i];
  p.normal = normal_;
  p.velocity = velocity_;
  return p;
}

TranslatingSphere::TranslatingSphere(const Point3& centre, double radius, const Point3& velocity)
    : TranslatingObstacle(velocity), centre_(centre), radius_(radius) {
  if (!(radius > 0.0)) throw std::invalid_argument("TranslatingSphere: radius must be positive");
}

ObstacleProjection TranslatingSphere::project(const Point3& x, double t) const {
  ObstacleProjection p;
  Point3 offset;
  for (int i = 0; i < 3; ++i) offset[i] = x[i] - centre_[i] - velocity_[i] * t;
  const double distance = norm(offset);
  if (!(distance > 0.0)) throw std::domain_error("TranslatingSphere: point at the centre has no normal");
  p.gap = distance - radius_;
  for (int i = 0; i < 3; ++i) p.normal[i] = offset[i] / distance;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) p.normal_gradient[3 * i + j] = ((i == j ? 1.0 : 0.0) - p.normal[i] * p.normal[j]) / distance;
  p.velocity = velocity_;
  return p;
}

OffsetObstacle::OffsetObstacle(std::shared_ptr<const RigidObstacle> obstacle, const Point3& offset)
    : obstacle_(std::move(obstacle)), offset_(offset) {}

ObstacleProjection OffsetObstacle::project(const Point3& x, double t) const { return obstacle_->project(shifted(x), t); }

Point3 OffsetObstacle::to_body(const Point3& x, double t) const { return obstacle_->to_body(shifted(x), t); }

Point3 OffsetObstacle::from_body(const Point3& xi, double t) const {
  const Point3 x = obstacle_->from_body(xi, t);
  return {x[0] + offset_[0], x[1] + offset_[1], x[2] + offset_[2]};
}

}  // namespace needlefem::contact
