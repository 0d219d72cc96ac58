// Why a file could not be written, as one line of ours. The system gives an errno; HDF5 gives a
// failing call -1 and, by default, prints its whole error stack (a dozen lines) to stderr, while
// the reason itself is in that stack: for a failed write or open, HDF5's sec2 file driver records
// the errno ("file write failed: ..., errno = 28, error message = 'No space left on device'").
#pragma once

#include <hdf5.h>

#include <string>

namespace needlefem::io {

// While alive, HDF5 prints nothing by itself: the caller reports one line.
class QuietHdf5Errors {
 public:
  QuietHdf5Errors();
  ~QuietHdf5Errors();
  QuietHdf5Errors(const QuietHdf5Errors&) = delete;
  QuietHdf5Errors& operator=(const QuietHdf5Errors&) = delete;

 private:
  H5E_auto2_t function_ = nullptr;
  void* data_ = nullptr;
};

// Why the HDF5 call that has just failed did, as a clause: the system's reason when HDF5
// recorded an errno ("no space left on device"), else HDF5's innermost description, else
// "unknown HDF5 error". Call it before any other HDF5 call: each one clears the stack.
std::string hdf5_failure_reason();

// The system's reason for an errno value, as a clause: "no space left on device".
std::string system_reason(int error);

}  // namespace needlefem::io
