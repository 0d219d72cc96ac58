// IDA's and its GMRES's vector operations on a sequential PETSc state vector, run on the OpenMP
// threads. NVECTOR_PETSC maps them to PETSc's Vec operations, which run on one thread; on the
// 736k-long brain-tip state (92 % of it Prony variables) they are memory-bound, and one thread
// reads 15 GB/s where two read 28-31 GB/s (measured on the second benchmark machine,
// docs/speed.md). There, outside the residual and preconditioner callbacks, IDA and GMRES spent
// 16 ms per GMRES iteration of the default frictional case, 23 % of its integration.
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
// Measured on 736k entries (second benchmark machine), PETSc's / these on one thread / on two:
// linear sum 0.59 / 0.61 / 0.35 ms, dot product 0.37–0.39 / 0.39 / 0.21 ms, weighted RMS norm
// 1.9–2.0 / 0.38 / 0.23 ms (the sums run eight lanes: one running sum is latency-bound, 0.52 ms).
bool use_threaded_vector_operations(N_Vector v);

}  // namespace needlefem
