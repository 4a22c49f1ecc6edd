// A one-line progress bar on stderr, drawn only when stderr is a terminal.
#pragma once

namespace reeve {

class ProgressBar {
 public:
  explicit ProgressBar(int total);
  ~ProgressBar();
  void update(int done);

 private:
  int total_;
  bool enabled_;
};

}  // namespace reeve
