#pragma once
// Progress on stderr: a bar with percentage and ETA per stage on a terminal,
// one line per finished stage otherwise (logs stay readable). Ctrl-C asks the
// running bake to stop at its next poll.
#include <chrono>
#include <string>

#include "bounce/progress.h"

namespace bounce::cli {

class ConsoleProgress {
 public:
  explicit ConsoleProgress(bool quiet);
  ~ConsoleProgress();
  Progress& progress() { return progress_; }

 private:
  bool on_report(const std::string& stage, double fraction);
  bool quiet_;
  bool tty_;
  Progress progress_;
  std::string stage_;
  std::chrono::steady_clock::time_point stage_start_;
};

}  // namespace bounce::cli
