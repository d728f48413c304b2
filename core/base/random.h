#pragma once
// Small deterministic random streams: every voxel, row or pair gets its own
// stream from a hash of (seed, index), so results do not depend on thread
// scheduling.
#include <cstdint>

namespace bounce {

inline std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

class Rng {
 public:
  Rng(std::uint64_t seed, std::uint64_t stream) : state_(splitmix64(seed ^ splitmix64(stream))) {}
  std::uint64_t next() { return state_ = splitmix64(state_); }
  // Uniform in [0, 1).
  float uniform() { return static_cast<float>(next() >> 40) * (1.0f / 16777216.0f); }

 private:
  std::uint64_t state_;
};

}  // namespace bounce
