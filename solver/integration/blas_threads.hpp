// OpenBLAS's thread count, set for a scope. needlefem runs BLAS on one thread (app/main.cpp:
// OpenBLAS's idle threads spin against the OpenMP element loops); code whose own OpenMP threads
// each call BLAS asks for one thread, and a double-precision factorisation whose large BLAS-3
// calls are its work asks for the cores. Other BLAS libraries have no such call: the scope then
// does nothing.
#pragma once

namespace needlefem {

class BlasThreads {
 public:
  explicit BlasThreads(int threads);
  ~BlasThreads();
  BlasThreads(const BlasThreads&) = delete;
  BlasThreads& operator=(const BlasThreads&) = delete;

 private:
  int previous_ = 0;  // 0: nothing to restore
};

}  // namespace needlefem
