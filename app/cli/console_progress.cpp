#include "console_progress.h"

#include <unistd.h>

#include <csignal>
#include <cstdio>

namespace bounce::cli {

namespace {

Progress* g_active = nullptr;

extern "C" void on_sigint(int) {
  // Only an atomic store: async-signal-safe. The bake throws Cancelled at
  // its next poll and the writer removes its temporary folder.
  if (g_active) g_active->request_stop();
}

}  // namespace

ConsoleProgress::ConsoleProgress(bool quiet)
    : quiet_(quiet),
      tty_(::isatty(STDERR_FILENO) != 0),
      progress_([this](const std::string& s, double f) { return on_report(s, f); }) {
  g_active = &progress_;
  std::signal(SIGINT, on_sigint);
  std::signal(SIGTERM, on_sigint);
}

ConsoleProgress::~ConsoleProgress() {
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  g_active = nullptr;
}

bool ConsoleProgress::on_report(const std::string& stage, double fraction) {
  if (quiet_) return true;
  const auto now = std::chrono::steady_clock::now();
  if (stage != stage_) {
    stage_ = stage;
    stage_start_ = now;
  }
  const double elapsed = std::chrono::duration<double>(now - stage_start_).count();
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    char eta[32] = "";
    if (fraction > 0.02 && fraction < 1.0)
      std::snprintf(eta, sizeof eta, " ETA %.0fs", elapsed * (1.0 - fraction) / fraction);
    std::fprintf(stderr, "\r  %-34s [%.*s%*s] %3.0f%%%-12s", stage.c_str(), filled,
                 "##############################", kWidth - filled, "", 100.0 * fraction, eta);
    if (fraction >= 1.0) std::fprintf(stderr, " %.2fs\n", elapsed);
  } else if (fraction >= 1.0) {
    std::fprintf(stderr, "  %-34s done in %.2fs\n", stage.c_str(), elapsed);
  }
  std::fflush(stderr);
  return true;
}

}  // namespace bounce::cli
