#pragma once
// Nearest neighbours between patch sketches: the candidate lists that keep
// the tour construction and its local search near O(n k) instead of O(n^2).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace bounce {

inline float squared_distance(const float* a, const float* b, std::size_t dims) {
  float s = 0.0f;
  for (std::size_t t = 0; t < dims; ++t) {
    const float d = a[t] - b[t];
    s += d * d;
  }
  return s;
}

struct NeighbourLists {
  std::size_t k = 0;                 // neighbours per point
  std::vector<std::uint32_t> index;  // n x k, nearest first
  const std::uint32_t* of(std::size_t i) const { return index.data() + i * k; }
};

// The k nearest other points of each of n points (row-major, dims floats
// each) by Euclidean distance, nearest first, ties to the smaller index; k is
// clamped to n - 1. Exact (brute force): distances come in tiles from one
// sgemm (|a|^2 + |b|^2 - 2 a.b) and the few best candidates of each point are
// re-measured directly, so rounding in the sgemm form cannot reorder them.
// O(n^2 dims) flops, O(n k) memory plus a ~16 MB tile.
NeighbourLists nearest_neighbours(const float* points, std::size_t n, std::size_t dims,
                                  std::size_t k);

}  // namespace bounce
