// The threaded vector operations (integration/threaded_vector_ops.hpp) against NVECTOR_PETSC's
// own, on random vectors longer than the serial cut-off, with the output aliasing an input as
// IDA does; on two OpenMP threads, sums repeat bit for bit. (A distributed vector keeps PETSc's:
// test_ida_parallel.cpp.)
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <nvector/nvector_petsc.h>
#include <omp.h>
#include <petscvec.h>
#include <sundials/sundials_context.h>

#include "integration/threaded_vector_ops.hpp"

namespace needlefem {
namespace {

constexpr PetscInt kLength = 100003;  // above the serial cut-off, not a multiple of the threads

struct Vectors {
  explicit Vectors(int count) {
    SUNContext_Create(nullptr, &context);
    std::mt19937 generator(7);
    std::uniform_real_distribution<double> value(-2.0, 2.0);
    for (int k = 0; k < count; ++k) {
      Vec v = nullptr;
      VecCreateSeq(PETSC_COMM_SELF, kLength, &v);
      PetscScalar* data = nullptr;
      VecGetArray(v, &data);
      for (PetscInt i = 0; i < kLength; ++i) data[i] = value(generator);
      if (k == 2)  // a mask: about half positive
        for (PetscInt i = 0; i < kLength; ++i) data[i] = data[i] > 0.0 ? 1.0 : 0.0;
      VecRestoreArray(v, &data);
      petsc.push_back(N_VMake_Petsc(v, context));
      threaded.push_back(N_VClone(petsc.back()));
      VecCopy(v, N_VGetVector_Petsc(threaded.back()));
      vecs.push_back(v);
    }
    for (N_Vector t : threaded) use_threaded_vector_operations(t);
  }
  ~Vectors() {
    for (N_Vector t : threaded) N_VDestroy(t);
    for (N_Vector p : petsc) N_VDestroy(p);
    for (Vec v : vecs) VecDestroy(&v);
    SUNContext_Free(&context);
  }
  std::vector<double> values(N_Vector v) const {
    std::vector<double> out(kLength);
    const PetscScalar* data = nullptr;
    VecGetArrayRead(N_VGetVector_Petsc(v), &data);
    std::copy(data, data + kLength, out.begin());
    VecRestoreArrayRead(N_VGetVector_Petsc(v), &data);
    return out;
  }
  double largest_difference(N_Vector a, N_Vector b) const {
    const auto x = values(a), y = values(b);
    double largest = 0.0;
    for (PetscInt i = 0; i < kLength; ++i) largest = std::max(largest, std::abs(x[i] - y[i]) / (1.0 + std::abs(x[i])));
    return largest;
  }
  SUNContext context = nullptr;
  std::vector<Vec> vecs;
  std::vector<N_Vector> petsc, threaded;
};

TEST(ThreadedVectorOperations, ElementwiseOperationsAgreeWithPetscsIncludingInPlace) {
  omp_set_num_threads(2);
  Vectors v(4);
  auto& p = v.petsc;
  auto& t = v.threaded;
  // z = a x + b y into a third vector, then in place over x (IDA's y += h y').
  N_VLinearSum(0.7, p[0], -1.3, p[1], p[3]);
  N_VLinearSum(0.7, t[0], -1.3, t[1], t[3]);
  EXPECT_LT(v.largest_difference(p[3], t[3]), 1e-15);
  N_VLinearSum(1.0, p[3], 0.25, p[1], p[3]);
  N_VLinearSum(1.0, t[3], 0.25, t[1], t[3]);
  EXPECT_LT(v.largest_difference(p[3], t[3]), 1e-15);
  N_VScale(-3.5, p[3], p[3]);
  N_VScale(-3.5, t[3], t[3]);
  EXPECT_LT(v.largest_difference(p[3], t[3]), 1e-15);
  N_VProd(p[0], p[3], p[3]);
  N_VProd(t[0], t[3], t[3]);
  EXPECT_LT(v.largest_difference(p[3], t[3]), 1e-15);
  N_VDiv(p[3], p[1], p[3]);
  N_VDiv(t[3], t[1], t[3]);
  EXPECT_LT(v.largest_difference(p[3], t[3]), 1e-15);
  N_VConst(2.5, p[3]);
  N_VConst(2.5, t[3]);
  EXPECT_EQ(v.values(p[3]), v.values(t[3]));
}

TEST(ThreadedVectorOperations, ReductionsAgreeWithPetscsAndRepeatBitForBit) {
  omp_set_num_threads(2);
  Vectors v(3);
  auto& p = v.petsc;
  auto& t = v.threaded;
  const double dot = N_VDotProd(p[0], p[1]), norm = N_VWrmsNorm(p[0], p[1]),
               masked = N_VWrmsNormMask(p[0], p[1], p[2]), largest = N_VMaxNorm(p[0]);
  EXPECT_NEAR(N_VDotProd(t[0], t[1]), dot, 1e-12 * std::abs(dot) + 1e-12);
  EXPECT_NEAR(N_VWrmsNorm(t[0], t[1]), norm, 1e-13 * norm);
  EXPECT_NEAR(N_VWrmsNormMask(t[0], t[1], t[2]), masked, 1e-13 * masked);
  EXPECT_LT(masked, norm);  // the mask leaves out about half the terms
  EXPECT_EQ(N_VMaxNorm(t[0]), largest);
  for (int repeat = 0; repeat < 5; ++repeat) {
    EXPECT_EQ(N_VDotProd(t[0], t[1]), N_VDotProd(t[0], t[1]));
    EXPECT_EQ(N_VWrmsNorm(t[0], t[1]), N_VWrmsNorm(t[0], t[1]));
  }
}

TEST(ThreadedVectorOperations, ClonesInheritThem) {
  Vectors v(1);
  N_Vector clone = N_VClone(v.threaded[0]);
  EXPECT_EQ(clone->ops->nvlinearsum, v.threaded[0]->ops->nvlinearsum);
  EXPECT_EQ(clone->ops->nvwrmsnorm, v.threaded[0]->ops->nvwrmsnorm);
  EXPECT_NE(clone->ops->nvlinearsum, v.petsc[0]->ops->nvlinearsum);
  N_VDestroy(clone);
}

}  // namespace
}  // namespace needlefem
