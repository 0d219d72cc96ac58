// SIGINT and SIGTERM as a request to stop, so that a long loop (a replay, a run) ends at a point
// of its choosing: the device gets its zero-force frame, a run keeps every completed output
// time and says in summary.json that it was interrupted.
#pragma once

#include <atomic>
#include <stdexcept>
#include <string>

namespace needlefem {

// While alive, SIGINT and SIGTERM raise stop_flag() instead of killing the process (a sleeping
// loop wakes early with EINTR). With `second_signal_kills`, only the first signal is caught: a
// second of the same signal kills at once, for a user who cannot wait for the next stopping
// point. The previous handlers are restored on destruction.
class InterruptGuard {
 public:
  explicit InterruptGuard(bool second_signal_kills = false);
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  static const std::atomic<bool>& stop_flag();
  // The signal that raised the flag (SIGINT, SIGTERM), 0 while none has.
  static int signal_number();
};

// A loop that stopped on request. The command ends with status 128 + signal, as a shell
// reports a process the signal killed.
struct Interrupted : std::runtime_error {
  Interrupted(int signal_number, const std::string& what) : std::runtime_error(what), signal_number(signal_number) {}
  int signal_number;
};

// "SIGINT", "SIGTERM" (or "signal N").
std::string signal_name(int signal_number);

}  // namespace needlefem
