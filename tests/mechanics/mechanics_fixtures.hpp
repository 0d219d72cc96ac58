// Shared set-up of the mechanics tests: a meshed case and a backward-Euler driver (a stand-in
// for IDA in tests: it exercises the same residual / setup_jacobian / solve_jacobian calls).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <petscvec.h>

#include "case/case.hpp"
#include "model/scene_model.hpp"
#include "physics/mechanics/mechanics_system.hpp"

namespace needlefem::mechanics::testing {

// A case from TOML text, meshed into a fresh temporary folder, with its mechanics system.
struct Problem {
  Case input;
  SceneModel scene;
  std::unique_ptr<MechanicsSystem> system;
  Vec y = nullptr, ydot = nullptr;

  // `overrides` as on the command line (--set); the default makes Newton's solves exact.
  explicit Problem(const std::string& toml,
                   const std::vector<std::string>& overrides = {"integration.newton=modified"});
  ~Problem();
  Problem(const Problem&) = delete;
  Problem& operator=(const Problem&) = delete;

  // Backward-Euler steps from t0 to t1 (starting from y), Newton to convergence in each.
  // Returns false when a step's Newton iteration fails.
  bool advance(double t0, double t1, int steps);
  double displacement(int node, int component) const;
};

}  // namespace needlefem::mechanics::testing
