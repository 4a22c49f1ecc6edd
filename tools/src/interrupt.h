// SIGINT and SIGTERM as a request to stop after the current frame.
#pragma once

#include <csignal>

namespace reeve {

/// While alive, SIGINT and SIGTERM set a flag instead of ending the
/// process, so a run can finish the frame it is writing, close its outputs
/// and exit 128 + the signal. A second signal ends the process as usual
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

 private:
  struct sigaction old_int_{}, old_term_{};
};

}  // namespace reeve
