// Equations: scene_obstacle.hpp.
#include "physics/contact/scene_obstacle.hpp"

#include "physics/contact/needle_contact.hpp"

namespace needlefem::contact {

namespace {

constexpr double kMetresPerMm = 1e-3;

Point3 point_in_metres(const std::array<double, 3>& v) {
  return {v[0] * kMetresPerMm, v[1] * kMetresPerMm, v[2] * kMetresPerMm};
}

std::shared_ptr<const RigidObstacle> scene_obstacle(const ObstacleSpec& spec, const NeedleSpecs* needle) {
  const Point3 velocity = point_in_metres(spec.velocity_mm_per_s);
  switch (spec.kind) {
    case ObstacleKind::plane:
      return std::make_shared<TranslatingPlane>(point_in_metres(spec.point_mm), spec.normal, velocity);
    case ObstacleKind::sphere:
      return std::make_shared<TranslatingSphere>(point_in_metres(spec.point_mm), spec.radius_mm * kMetresPerMm,
                                                 velocity);
    case ObstacleKind::needle:
      return std::make_shared<OffsetObstacle>(needle_from_spec(*needle), point_in_metres(spec.point_mm));
    case ObstacleKind::none:
      break;
  }
  return nullptr;
}

}  // namespace

std::shared_ptr<PenaltyContact> scene_obstacle_contact(const ObstacleSpec& spec, const NeedleSpecs* needle,
                                                       const ContactParameters& parameters, const TetMesh& mesh) {
  auto obstacle = scene_obstacle(spec, needle);
  if (!obstacle) return nullptr;
  return std::make_shared<PenaltyContact>(mesh, spec.group, std::move(obstacle), parameters);
}

}  // namespace needlefem::contact
