#include "core/interrupt.hpp"

#include <atomic>
#include <csignal>

namespace vdec {

namespace {

// Lock-free, so that a store from a signal handler is safe (a plain int need not be).
std::atomic<int> requested{0};
static_assert(std::atomic<int>::is_always_lock_free);

void recordInterrupt(int signal) { requested.store(signal, std::memory_order_relaxed); }

}  // namespace

void installInterruptHandlers() {
  struct sigaction action = {};
  action.sa_handler = recordInterrupt;
  sigemptyset(&action.sa_mask);
  // SA_RESTART: a write interrupted by the signal goes on instead of failing with EINTR.
  action.sa_flags = SA_RESETHAND | SA_RESTART;
  for (const int signal : {SIGINT, SIGTERM}) {
    // A signal the parent ignores stays ignored (nohup, background jobs of a shell script).
    struct sigaction previous = {};
    if (sigaction(signal, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN) continue;
    sigaction(signal, &action, nullptr);
  }
}

int interruptSignal() { return requested.load(std::memory_order_relaxed); }

const char* signalName(int signal) {
  switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case 0: return "";
  }
  return "signal";
}

void setInterruptSignal(int signal) { requested.store(signal, std::memory_order_relaxed); }

}  // namespace vdec
