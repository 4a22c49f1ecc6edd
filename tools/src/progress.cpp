#include "progress.h"

#include <unistd.h>

#include <cstdio>

namespace reeve {

ProgressBar::ProgressBar(int total)
    : total_(total), enabled_(isatty(STDERR_FILENO) != 0), frame_start_(Clock::now()), last_draw_(frame_start_) {}

ProgressBar::~ProgressBar() {
  if (enabled_) std::fputs("\n", stderr);
}

void ProgressBar::update(int done) {
  done_ = done;
  if (!enabled_ || total_ <= 0) return;
  frame_start_ = last_draw_ = Clock::now();
  draw(done, "");
}

void ProgressBar::updateWithin(int substep, int substeps) {
  if (!enabled_ || total_ <= 0 || substep >= substeps) return;
  const Clock::time_point now = Clock::now();
  if (now - frame_start_ < kSlowFrame || now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  char detail[64];
  std::snprintf(detail, sizeof detail, ", frame %d: substep %d/%d", done_ + 1, substep, substeps);
  draw(done_ + static_cast<double>(substep) / substeps, detail);
}

void ProgressBar::draw(double done, const char* detail) {
  constexpr int width = 40;
  const int filled = static_cast<int>(done * width / total_);
  // Padded so a shorter line covers a longer one before it.
  std::fprintf(stderr, "\r[%.*s%*s] %d/%d frames%-36s", filled, "########################################",
               width - filled, "", done_, total_, detail);
  std::fflush(stderr);
}

}  // namespace reeve
