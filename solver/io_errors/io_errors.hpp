// Why a file could not be written, as one line of ours. The system gives an errno; HDF5 gives a
// failing call -1 and, by default, prints its whole error stack (a dozen lines) to stderr, while
// the reason itself is in that stack: for a failed write or open, HDF5's sec2 file driver records
// the errno ("file write failed: ..., errno = 28, error message = 'No space left on device'").
#pragma once

#include <hdf5.h>

#include <string>

namespace needlefem::io {

// From this call on, HDF5 prints nothing by itself for the rest of the process: every module
// that calls it checks each HDF5 result and reports a failure in one line of its own
// (hdf5_failure_reason). It is not switched back on afterwards: a file whose creation or write
// failed fails again when it is closed later, in a destructor after the failing scope has ended
// or by HDF5 itself at exit ("HDF5: infinite loop closing library"), and HDF5 prints those
// stacks whenever printing is on at that moment.
void stop_hdf5_error_printing();

// Starts HDF5 so that it never terminates by itself; to be called before MPI starts (PETSc).
// HDF5 1.10.8 terminates at MPI_Finalize when MPI was running when it started, else at exit, and
// its termination closes every file still open: a file whose flush failed (a full disk) could
// not be closed by its owner, and closing it again crashed in H5F__close_cb (SIGSEGV after the
// run's one-line error). Every file of needlefem's is closed by its owner, so the termination
// has nothing else to do.
void start_hdf5_without_termination();

// Why the HDF5 call that has just failed did, as a clause: the system's reason when HDF5
// recorded an errno ("no space left on device"), else HDF5's innermost description, else
// "unknown HDF5 error". Call it before any other HDF5 call: each one clears the stack.
std::string hdf5_failure_reason();

// The system's reason for an errno value, as a clause: "no space left on device".
std::string system_reason(int error);

}  // namespace needlefem::io
