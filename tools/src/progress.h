// A one-line progress bar on stderr, drawn only when stderr is a terminal.
#pragma once

#include <chrono>

namespace reeve {

class ProgressBar {
 public:
  explicit ProgressBar(int total);
  ~ProgressBar();
  /// `done` of the total frames are whole.
  void update(int done);
  /// Inside the frame after those done, `substep` of its `substeps` are
  /// done: once a frame has taken kSlowFrame, the line says so, at most
  /// ten times a second, so that a long frame shows it moves.
  void updateWithin(int substep, int substeps);

  static constexpr std::chrono::milliseconds kSlowFrame{500};

 private:
  using Clock = std::chrono::steady_clock;
  void draw(double done, const char* detail);

  int total_;
  bool enabled_;
  int done_ = 0;
  Clock::time_point frame_start_, last_draw_;
};

}  // namespace reeve
