#pragma once
// A small cell of one triangle's surface within one sample: what a near
// source and a spot of the final gather stand for (runtime/final_gather.h).
// The cell lattice's resolution is the caller's (near sources and spots use
// their own).
#include <cstddef>
#include <cstdint>

namespace bounce {

// The sample whose surface the rays landed on, the triangle they landed on
// (so that the mean landing point lies on that triangle and its normal is
// that triangle's) and the cell of the lattice they landed in.
struct SurfaceCellKey {
  std::int32_t sample, x, y, z;
  std::uint32_t triangle;
  bool operator==(const SurfaceCellKey&) const = default;
};

struct SurfaceCellKeyHash {
  std::size_t operator()(const SurfaceCellKey& k) const {
    std::uint64_t h = static_cast<std::uint32_t>(k.sample) * 0x9E3779B97F4A7C15ull;
    for (const std::int32_t v : {k.x, k.y, k.z, static_cast<std::int32_t>(k.triangle)})
      h = (h ^ static_cast<std::uint32_t>(v)) * 0xBF58476D1CE4E5B9ull;
    return static_cast<std::size_t>(h ^ (h >> 31));
  }
};

}  // namespace bounce
