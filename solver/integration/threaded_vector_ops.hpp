// IDA's and its GMRES's vector operations on a sequential PETSc state vector, run on the OpenMP
// threads. NVECTOR_PETSC maps them to PETSc's Vec operations, which run on one thread; on the
// brain-tip state (measured on 736k unknowns, when the Prony variables were in it; 235k at the
// default case's level 2 now) they are memory-bound, and two threads
// read nearly twice the bandwidth of one, so IDA's and GMRES's own work per iteration shrinks
// (the measurements: docs/speed.md, "What is in place").
//
// The operations replaced are the ones IDA and SPGMR call per Newton or GMRES iteration: linear
// sum, constant, product, quotient, scaling, dot product, weighted RMS norm (also masked) and
// max norm. Elementwise results are those of NVECTOR_PETSC exactly; sums are taken over a fixed
// split of the vector, one part per thread, and added in thread order, so a run with the same
// thread count repeats bit for bit (an OpenMP reduction clause adds in no fixed order).
#pragma once

#include <sundials/sundials_nvector.h>

namespace needlefem {

// Replaces the operations above in v's operation table, which every clone of v copies (IDA
// clones its work vectors from the initial state, SPGMR its Krylov basis). Only for a vector on
// one MPI rank; otherwise v is left as it is. Returns whether it replaced them.
// The sums run eight lanes: one running sum is latency-bound (timings: docs/speed.md).
bool use_threaded_vector_operations(N_Vector v);

}  // namespace needlefem
