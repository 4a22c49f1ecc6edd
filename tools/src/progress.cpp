#include "progress.h"

#include <unistd.h>

#include <cstdio>

namespace reeve {

ProgressBar::ProgressBar(int total) : total_(total), enabled_(isatty(STDERR_FILENO) != 0) {}

ProgressBar::~ProgressBar() {
  if (enabled_) std::fputs("\n", stderr);
}

void ProgressBar::update(int done) {
  if (!enabled_ || total_ <= 0) return;
  constexpr int width = 40;
  const int filled = done * width / total_;
  std::fprintf(stderr, "\r[%.*s%*s] %d/%d frames", filled, "########################################",
               width - filled, "", done, total_);
  std::fflush(stderr);
}

}  // namespace reeve
