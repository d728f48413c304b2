#include "base/stage_stats.h"

#include <fstream>
#include <string>

namespace bounce {

std::uint64_t peak_rss_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) * 1024ull;
  }
  return 0;
}

bool reset_peak_rss() {
  // Writing "5" to clear_refs resets VmHWM to the current RSS (Linux >= 4.0).
  std::ofstream clear("/proc/self/clear_refs");
  if (!clear) return false;
  clear << "5";
  return static_cast<bool>(clear.flush());
}

StageTimer::StageTimer(std::string name)
    : name_(std::move(name)), start_(std::chrono::steady_clock::now()) {
  reset_peak_rss();
}

StageStats StageTimer::finish() const {
  StageStats s;
  s.name = name_;
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  s.peak_rss_bytes = peak_rss_bytes();
  return s;
}

}  // namespace bounce
