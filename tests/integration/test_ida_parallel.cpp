// IdaIntegrator on distributed PETSc vectors (run under mpiexec -n 2): four Maxwell-solid
// material points per rank, each with its own strain amplitude, one block-diagonal MPIAIJ
// Newton matrix factored by parallel MUMPS. Every point must match its closed form, and the
// ranks must agree on every step (IDA's norms are global reductions).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <mpi.h>

#include <nvector/nvector_petsc.h>
#include <sundials/sundials_context.h>

#include "integration/ida_integrator.hpp"
#include "integration/threaded_vector_ops.hpp"
#include "maxwell_solid.hpp"

namespace needlefem {
namespace {

using testing::MaxwellSolid;
using testing::MaxwellSolidSystem;

TEST(IdaIntegratorParallel, DistributedMaxwellSolidsMatchTheirClosedForms) {
  int ranks = 0;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  constexpr double rtol = 1e-6;
  MaxwellSolidSystem system({}, {}, PETSC_COMM_WORLD, 4);
  IdaOptions options;
  options.relative_tolerance = rtol;
  options.absolute_tolerance = 1e-10;
  IdaIntegrator ida(system, options, 0.0, PETSC_COMM_WORLD);

  double worst = 0.0;
  for (double t : {0.05, 0.1, 0.5, 1.0, 2.0}) {
    ida.advance_to(t);
    const double* y = nullptr;
    petsc_check(VecGetArrayRead(ida.state(), &y), "VecGetArrayRead");
    for (PetscInt b = 0; b < system.blocks(); ++b) {
      const MaxwellSolid point = system.point(b);
      const auto exact = point.exact(t);
      worst = std::max({worst, std::abs(y[3 * b] - exact[0]) / point.peak_stress(),
                        std::abs(y[3 * b + 1] - exact[1]) / point.eps0, std::abs(y[3 * b + 2] - exact[2]) / point.eps0});
    }
    petsc_check(VecRestoreArrayRead(ida.state(), &y), "VecRestoreArrayRead");
  }
  double worst_global = 0.0;
  MPI_Allreduce(&worst, &worst_global, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);

  const auto c = ida.counters();
  long steps[2] = {c.steps, -c.steps}, extremes[2] = {0, 0};
  MPI_Allreduce(steps, extremes, 2, MPI_LONG, MPI_MAX, PETSC_COMM_WORLD);
  PetscPrintf(PETSC_COMM_WORLD, "%d ranks, 8 points: max relative error %.3e, steps %ld, Jacobian setups %ld\n",
              ranks, worst_global, c.steps, c.jacobian_setups);
  EXPECT_EQ(ranks, 2) << "run under mpiexec -n 2";
  EXPECT_LT(worst_global, 20.0 * rtol);
  EXPECT_EQ(extremes[0], -extremes[1]) << "ranks disagree on the number of steps";
  EXPECT_EQ(system.jacobian_setups(), c.jacobian_setups);
}

// The threaded vector operations sum only their own rank's part: a distributed vector keeps
// NVECTOR_PETSC's, whose reductions span the ranks.
TEST(IdaIntegratorParallel, DistributedVectorsKeepPetscsOperations) {
  SUNContext context = nullptr;
  ASSERT_EQ(SUNContext_Create(&PETSC_COMM_WORLD, &context), 0);
  Vec v = nullptr;
  petsc_check(VecCreateMPI(PETSC_COMM_WORLD, 10, PETSC_DETERMINE, &v), "VecCreateMPI");
  N_Vector nv = N_VMake_Petsc(v, context);
  const auto petsc_linear_sum = nv->ops->nvlinearsum;
  EXPECT_FALSE(use_threaded_vector_operations(nv));
  EXPECT_EQ(nv->ops->nvlinearsum, petsc_linear_sum);
  N_VDestroy(nv);
  VecDestroy(&v);
  SUNContext_Free(&context);
}

}  // namespace
}  // namespace needlefem
