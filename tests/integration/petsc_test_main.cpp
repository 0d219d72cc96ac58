// GoogleTest main for tests that need PETSc: arguments GoogleTest does not consume go to
// PETSc, e.g. `test_integration_ida -nf_ksp_view`.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "integration/petsc_session.hpp"

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  const std::vector<std::string> petsc_options(argv + 1, argv + argc);
  needlefem::PetscSession session(petsc_options);
  return RUN_ALL_TESTS();
}
