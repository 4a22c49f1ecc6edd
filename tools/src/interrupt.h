// SIGINT and SIGTERM as a request to stop, read by World::step between
// solver iterations and after every frame.
#pragma once

#include <atomic>
#include <csignal>

namespace reeve {

/// While alive, SIGINT and SIGTERM set a flag instead of ending the
/// process, so a run can end the substep under way (World::setInterruptFlag
/// with flag()), close its outputs and exit 128 + the signal. A second signal ends the process as usual
/// (SA_RESETHAND). A signal the process inherited as ignored (nohup, a
/// background job of a shell without job control) stays ignored.
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  /// The signal received (SIGINT or SIGTERM), 0 while none was.
  int received() const;
  /// The flag the handler sets to the signal, for World::setInterruptFlag.
  static const std::atomic<int>* flag();

 private:
  struct sigaction old_int_{}, old_term_{};
};

}  // namespace reeve
