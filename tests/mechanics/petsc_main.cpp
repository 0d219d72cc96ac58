// GoogleTest main inside PetscInitialize/PetscFinalize (the mechanics system uses PETSc).
#include <gtest/gtest.h>
#include <petscsys.h>

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (PetscInitializeNoArguments() != 0) return 1;
  const int failed = RUN_ALL_TESTS();
  PetscFinalize();
  return failed;
}
