#include "integration/blas_threads.hpp"

#include <dlfcn.h>

namespace needlefem {

namespace {

// OpenBLAS's calls, looked up once; null under another BLAS.
struct OpenBlasThreadCalls {
  OpenBlasThreadCalls()
      : set(reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))),
        get(reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"))) {}
  void (*set)(int);
  int (*get)();
};

const OpenBlasThreadCalls& openblas() {
  static const OpenBlasThreadCalls calls;
  return calls;
}

}  // namespace

BlasThreads::BlasThreads(int threads) {
  const OpenBlasThreadCalls& calls = openblas();
  if (!calls.set || !calls.get) return;
  previous_ = calls.get();
  if (previous_ != threads) calls.set(threads);
}

BlasThreads::~BlasThreads() {
  const OpenBlasThreadCalls& calls = openblas();
  if (previous_ > 0 && calls.get() != previous_) calls.set(previous_);
}

}  // namespace needlefem
