#include "case/specs/contact_spec.hpp"

#include <utility>
#include <vector>

#include "case/case.hpp"
#include "case/specs/choice.hpp"

namespace needlefem {

namespace {

// Each key's choices (schema.cpp) with their enumerators.
const std::array kContactModes{std::pair{"frictional", ContactMode::frictional}, std::pair{"tied", ContactMode::tied}};
const std::array kFrictionTangents{std::pair{"secant", FrictionTangent::secant},
                                   std::pair{"consistent", FrictionTangent::consistent}};
const std::array kFrictionLaws{std::pair{"return-map", FrictionLaw::return_map},
                               std::pair{"velocity", FrictionLaw::velocity}};
const std::array kNormalEnforcements{std::pair{"penalty", NormalEnforcement::penalty},
                                     std::pair{"augmented", NormalEnforcement::augmented}};
const std::array kObstacleKinds{std::pair{"none", ObstacleKind::none}, std::pair{"plane", ObstacleKind::plane},
                                std::pair{"sphere", ObstacleKind::sphere}, std::pair{"needle", ObstacleKind::needle}};

std::array<double, 3> triple(const Case& c, const std::string& key) {
  const std::vector<double> v = c.reals(key);  // the schema gives these keys three entries
  return {v[0], v[1], v[2]};
}

}  // namespace

ContactSpec parse_contact_spec(const Case& c) {
  return {
      .mode = parse_choice(c, "contact.mode", kContactModes),
      .friction_coefficient = c.real("contact.friction_coefficient"),
      .penalty_factor = c.real("contact.penalty_factor"),
      .penalty_smoothing = c.real("contact.penalty_smoothing"),
      .elastic_slip = c.real("contact.elastic_slip"),
      .rate_strengthening_s_per_m = c.real("contact.rate_strengthening_s_per_m"),
      .slip_velocity_regularisation_mm_per_s = c.real("contact.slip_velocity_regularisation_mm_per_s"),
      .friction_tangent = parse_choice(c, "contact.friction_tangent", kFrictionTangents),
      .friction_law = parse_choice(c, "contact.friction_law", kFrictionLaws),
      .normal_enforcement = parse_choice(c, "contact.normal_enforcement", kNormalEnforcements),
  };
}

NeedleDeflectionCheckSpec parse_needle_deflection_check_spec(const Case& c) {
  return {.origin = c.origin(),
          .enabled = c.flag("needle.deflection_check"),
          .youngs_modulus_gpa = c.real("needle.youngs_modulus_gpa"),
          .poisson_ratio = c.real("needle.poisson_ratio")};
}

ObstacleSpec parse_obstacle_spec(const Case& c) {
  const ObstacleSpec spec{
      .kind = parse_choice(c, "obstacle.kind", kObstacleKinds),
      .group = c.text("obstacle.group"),
      .point_mm = triple(c, "obstacle.point_mm"),
      .normal = triple(c, "obstacle.normal"),
      .radius_mm = c.real("obstacle.radius_mm"),
      .velocity_mm_per_s = triple(c, "obstacle.velocity_mm_per_s"),
  };
  if (spec.kind == ObstacleKind::plane && spec.normal == std::array{0.0, 0.0, 0.0})
    throw c.error("obstacle.normal", "must not be zero");
  return spec;
}

const char* obstacle_kind_name(ObstacleKind kind) { return choice_name(kObstacleKinds, kind); }

}  // namespace needlefem
