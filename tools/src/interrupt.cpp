#include "interrupt.h"

namespace reeve {
namespace {

// Lock-free, so a signal handler may store to it (and World::step read it).
std::atomic<int> g_received{0};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void onInterrupt(int signal) { g_received = signal; }

void install(int signal, struct sigaction& old) {
  sigaction(signal, nullptr, &old);
  if (old.sa_handler == SIG_IGN) return;
  struct sigaction action {};
  action.sa_handler = onInterrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART | SA_RESETHAND;  // writes carry on; a second signal ends the process
  sigaction(signal, &action, nullptr);
}

}  // namespace

InterruptGuard::InterruptGuard() {
  g_received = 0;
  install(SIGINT, old_int_);
  install(SIGTERM, old_term_);
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &old_int_, nullptr);
  sigaction(SIGTERM, &old_term_, nullptr);
}

int InterruptGuard::received() const { return g_received.load(); }

const std::atomic<int>* InterruptGuard::flag() { return &g_received; }

}  // namespace reeve
