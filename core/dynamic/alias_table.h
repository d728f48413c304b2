#pragma once
// Walker's alias method (Walker 1974, built with Vose's O(n) two-worklist
// construction): a discrete distribution over n outcomes as n (probability,
// alias) pairs, sampled in O(1) with one uniform index i and one uniform u:
// outcome i if u < probability[i], else alias[i]. Temporal radiosity turns
// every row of the multi-bounce matrix into one, as published temporal radiosity does.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "base/progress.h"

namespace bounce {

// One slot of a table. Probability and alias side by side: a draw reads one
// 8-byte slot at a random index, one cache miss instead of two (the draws
// are latency-bound: they dominate a frame's time).
struct AliasEntry {
  float probability;
  std::uint32_t alias;
};
static_assert(sizeof(AliasEntry) == 8, "the OpenCL kernel reads 8-byte slots");

// Builds the table of `weights` (n entries) into table[0..n); returns the weights' sum in float64.
// Negative weights (a rounding artefact of the LU, T >= 0 in exact arithmetic) count as zero. An
// all-zero row gets probability 1 everywhere (it is never sampled: its sum
// scales the estimate to 0). `work`: scratch, resized to n.
double build_alias_row(const float* weights, std::size_t n, AliasEntry* table,
                       std::vector<std::uint32_t>& work);

// Outcome of `table` for index i and coin u in [0, 1).
inline std::uint32_t alias_sample(const AliasEntry* table, std::uint32_t i, float u) {
  return u < table[i].probability ? i : table[i].alias;
}

// One alias table per row of a row-major rows x cols matrix.
struct AliasTables {
  std::size_t rows = 0, cols = 0;
  std::vector<AliasEntry> entries;  // rows x cols
  std::vector<float> row_sum;       // rows
  std::size_t bytes() const {
    return entries.size() * sizeof(AliasEntry) + row_sum.size() * sizeof(float);
  }
};

// Rows in parallel (OpenMP); `progress` (may be null) advances once per row.
// Throws bounce::Error when cols exceeds 2^32 - 1, Cancelled on a stop.
AliasTables build_alias_tables(const float* matrix, std::size_t rows, std::size_t cols,
                               Progress* progress = nullptr);

}  // namespace bounce
