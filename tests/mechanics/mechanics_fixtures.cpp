#include "mechanics_fixtures.hpp"

#include <atomic>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include <unistd.h>

#include "case/specs/boundary_spec.hpp"
#include "case/specs/contact_spec.hpp"
#include "case/specs/integration_spec.hpp"
#include "case/specs/mesh_spec.hpp"
#include "case/specs/pressure_spec.hpp"
#include "integration/options_from_spec.hpp"

namespace needlefem::mechanics::testing {

namespace {

std::filesystem::path fresh_folder() {
  static std::atomic<int> counter{0};
  auto folder = std::filesystem::temp_directory_path() /
                ("needlefem_mechanics_" + std::to_string(getpid()) + "_" + std::to_string(counter++));
  std::filesystem::create_directories(folder);
  return folder;
}

// The case's mechanics as a run parses it (run/run_specs.cpp).
MechanicsSpec mechanics_spec(const Case& input) {
  const MeshSpec mesh = parse_mesh_spec(input);
  return parse_mechanics_spec(input, mesh, parse_loading_spec(input, mesh.scene_kind), parse_contact_spec(input).mode);
}

SceneModel meshed(const Case& input) {
  const auto folder = fresh_folder();
  const MeshSpec mesh = parse_mesh_spec(input);
  SceneModel scene = load_scene_model(mesh, mechanics_spec(input).boundary.groups, parse_pressure_spec(input),
                                      parse_obstacle_spec(input), folder, nullptr);
  std::filesystem::remove_all(folder);
  return scene;
}

double displacement_norm(const MechanicsSystem& system, Vec v) {
  const PetscScalar* values = nullptr;
  VecGetArrayRead(v, &values);
  double sum = 0.0;
  for (PetscInt i = 0; i < system.displacement_dofs(); ++i) sum += values[i] * values[i];
  VecRestoreArrayRead(v, &values);
  return std::sqrt(sum);
}

}  // namespace

// advance() is a full Newton iteration on the system's solves, so they must be exact: the
// modified-Newton setting (the default Krylov one makes them single-precision preconditioner
// solves, newton_matrix_factor.hpp).
Problem::Problem(const std::string& toml, const std::vector<std::string>& overrides)
    : input(Case::parse(toml, "test", overrides)),
      scene(meshed(input)),
      system(MechanicsSystem::from_spec(mechanics_spec(input), scene.mesh)) {
  system->use_newton_matrix_options(newton_matrix_options_from_spec(parse_integration_spec(input)));
  VecCreateSeq(PETSC_COMM_SELF, system->local_size(), &y);
  VecDuplicate(y, &ydot);
  system->initial_state(0.0, y, ydot);
}

Problem::~Problem() {
  VecDestroy(&y);
  VecDestroy(&ydot);
}

bool Problem::advance(double t0, double t1, int steps) {
  Vec y_old, residual, correction;
  VecDuplicate(y, &y_old);
  VecDuplicate(y, &residual);
  VecDuplicate(y, &correction);
  const double h = (t1 - t0) / steps;
  bool converged = true;
  for (int step = 1; step <= steps && converged; ++step) {
    const double t = t0 + step * h;
    VecCopy(y, y_old);
    converged = false;
    for (int iteration = 0; iteration < 25 && !converged; ++iteration) {
      VecWAXPY(ydot, -1.0, y_old, y);  // y' = (y - y_old)/h
      VecScale(ydot, 1.0 / h);
      if (system->residual(t, y, ydot, residual) != DaeStatus::ok) break;
      if (system->setup_jacobian(t, y, ydot, 1.0 / h) != DaeStatus::ok) break;
      if (system->solve_jacobian(residual, correction) != DaeStatus::ok) break;
      VecAXPY(y, -1.0, correction);
      // Over the displacements: the element pressures follow them as U'(θ), with a round-off
      // floor of K times that of θ (1e-7 Pa at K = 1e9 Pa) that a norm mixing metres and pascals
      // would compare with the displacements' 1e-10.
      const double step_norm = displacement_norm(*system, correction), state_norm = displacement_norm(*system, y);
      // Newton converges quadratically to a round-off floor of ~1e-11 at K/mu = 1e6.
      converged = step_norm <= 1e-10 * state_norm;
    }
    if (converged) system->accept_step(t, y, ydot);  // as IDA does after each step
  }
  if (converged) {
    VecWAXPY(ydot, -1.0, y_old, y);
    VecScale(ydot, 1.0 / h);
  }
  VecDestroy(&y_old);
  VecDestroy(&residual);
  VecDestroy(&correction);
  return converged;
}

double Problem::displacement(int node, int component) const {
  const PetscScalar* values = nullptr;
  VecGetArrayRead(y, &values);
  const double u = values[system->dof_map().dof(node, component)];
  VecRestoreArrayRead(y, &values);
  return u;
}

}  // namespace needlefem::mechanics::testing
