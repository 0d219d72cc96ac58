// Scoped read-only and writable views of a PETSc vector's local array: acquired in the
// constructor, restored in the destructor, so no early return or exception leaks a view.
#pragma once

#include <petscvec.h>

#include "integration/petsc_session.hpp"

namespace needlefem {

class ReadArray {
 public:
  explicit ReadArray(Vec v) : v_(v) { petsc_check(VecGetArrayRead(v_, &data_), "VecGetArrayRead"); }
  ~ReadArray() { VecRestoreArrayRead(v_, &data_); }
  ReadArray(const ReadArray&) = delete;
  ReadArray& operator=(const ReadArray&) = delete;
  const double* data() const { return data_; }

 private:
  Vec v_;
  const PetscScalar* data_ = nullptr;
};

class WriteArray {
 public:
  explicit WriteArray(Vec v) : v_(v) { petsc_check(VecGetArray(v_, &data_), "VecGetArray"); }
  ~WriteArray() { VecRestoreArray(v_, &data_); }
  WriteArray(const WriteArray&) = delete;
  WriteArray& operator=(const WriteArray&) = delete;
  double* data() const { return data_; }

 private:
  Vec v_;
  PetscScalar* data_ = nullptr;
};

}  // namespace needlefem
