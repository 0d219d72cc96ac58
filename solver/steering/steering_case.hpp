// The steering problem of a case: its needle tip and steering specs (case/specs/needle_tip_spec.hpp,
// steering_spec.hpp) turned into SI model, schedule, run and scene, with the cross-key rules of a
// magnet schedule.
#pragma once

#include <string>

#include "case/case.hpp"
#include "steering/steering_path.hpp"

namespace needlefem::steering {

struct SteeringSetup {
  SteeringModel model;
  MagnetSchedule schedule;
  SteeringRun run;
  ObstacleScene scene;
  double target_tolerance_m = 0.0;
  std::string origin;  // the case's, for the CaseErrors of the schedule where it is used (run/hinge_coupling.cpp)
};

// Throws CaseError ("FILE: key 'steering.KEY': reason") when the schedule is malformed: both or
// neither axis with magnet tables, tables of different lengths, an axis that does not increase
// strictly, a distance whose turning angle exceeds steering.max_turning_angle_deg, a pull along
// the shaft.
SteeringSetup steering_setup_from_case(const Case& input);

}  // namespace needlefem::steering
