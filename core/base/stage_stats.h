#pragma once
// Wall time and peak resident memory of one stage of a bake, for the manifest
// and `bounce bench bake`.
#include <chrono>
#include <cstdint>
#include <string>

namespace bounce {

struct StageStats {
  std::string name;
  double seconds = 0.0;
  std::uint64_t peak_rss_bytes = 0;  // high-water mark of the process during the stage
  // Distributed bake: the highest of the other ranks' peaks in their stage of
  // the same name (0: a single process, or no such stage on the other ranks).
  std::uint64_t peak_rss_bytes_other_ranks = 0;
};

// Current peak resident set size of this process (VmHWM), in bytes.
std::uint64_t peak_rss_bytes();
// Resets the kernel's peak-RSS counter so the next stage measures its own peak.
// Returns false where the kernel does not allow it (the peak then is cumulative).
bool reset_peak_rss();

// Measures one stage: construct at its start, call finish() at its end.
class StageTimer {
 public:
  explicit StageTimer(std::string name);
  StageStats finish() const;

 private:
  std::string name_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace bounce
