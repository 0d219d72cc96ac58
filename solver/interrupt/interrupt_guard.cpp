#include "interrupt/interrupt_guard.hpp"

#include <signal.h>

namespace needlefem {

namespace {

std::atomic<bool> interrupt_requested{false};
std::atomic<int> interrupt_signal{0};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
              "the signal handler needs lock-free atomics");

struct sigaction previous_sigint {}, previous_sigterm{};

extern "C" void request_stop(int signal_number) {
  interrupt_signal.store(signal_number);
  interrupt_requested.store(true);
}

}  // namespace

InterruptGuard::InterruptGuard(bool second_signal_kills) {
  interrupt_requested.store(false);
  interrupt_signal.store(0);
  struct sigaction action {};
  action.sa_handler = request_stop;
  sigemptyset(&action.sa_mask);
  // No SA_RESTART: a sleeping loop must wake with EINTR. SA_RESETHAND: the handler goes back to
  // the default (terminate) once it has run.
  action.sa_flags = second_signal_kills ? SA_RESETHAND : 0;
  sigaction(SIGINT, &action, &previous_sigint);
  sigaction(SIGTERM, &action, &previous_sigterm);
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &previous_sigint, nullptr);
  sigaction(SIGTERM, &previous_sigterm, nullptr);
}

const std::atomic<bool>& InterruptGuard::stop_flag() { return interrupt_requested; }

int InterruptGuard::signal_number() { return interrupt_signal.load(); }

std::string signal_name(int signal_number) {
  switch (signal_number) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "signal " + std::to_string(signal_number);
  }
}

}  // namespace needlefem
