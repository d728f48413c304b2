#pragma once
// The counter-based random stream of temporal radiosity, shared bit for bit
// by the C++ path and kernels/temporal_radiosity.cl: every (seed, frame, row,
// sample, lane) has its own 32-bit value, a hash of the counter rather than a
// state that advances, so any work-item can draw any sample in any order and
// both paths draw the same samples. The mixer is Chris Wellons' "lowbias32"
// (two multiply-xorshift rounds, bias ~0.17 of the ideal avalanche); each
// counter field is folded in by another round.
#include <cstdint>

namespace bounce {

inline std::uint32_t hash32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// The part of the counter that is fixed for one row of one frame: hoisted
// out of the sample loop (one round per sample instead of four).
inline std::uint32_t row_stream(std::uint32_t seed, std::uint32_t frame, std::uint32_t row,
                                std::uint32_t lane) {
  std::uint32_t h = hash32(seed ^ (lane * 0x9e3779b9u));
  h = hash32(h ^ frame);
  return hash32(h ^ row);
}

inline std::uint32_t sample_hash(std::uint32_t seed, std::uint32_t frame, std::uint32_t row,
                                 std::uint32_t sample, std::uint32_t lane) {
  return hash32(row_stream(seed, frame, row, lane) ^ sample);
}

// A uniform index in [0, n): the high word of h * n (bias below n / 2^32).
inline std::uint32_t hash_to_index(std::uint32_t h, std::uint32_t n) {
  return static_cast<std::uint32_t>((static_cast<std::uint64_t>(h) * n) >> 32);
}

// A uniform float in [0, 1) with 24 bits, exact in float.
inline float hash_to_unit(std::uint32_t h) {
  return static_cast<float>(h >> 8) * (1.0f / 16777216.0f);
}

}  // namespace bounce
