#include "dynamic/alias_table.h"

#include <limits>
#include <string>

#include "base/error.h"

namespace bounce {

double build_alias_row(const float* weights, std::size_t n, AliasEntry* table,
                       std::vector<std::uint32_t>& work) {
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) sum += weights[i] > 0.0f ? weights[i] : 0.0f;
  for (std::size_t i = 0; i < n; ++i) table[i] = {1.0f, static_cast<std::uint32_t>(i)};
  if (!(sum > 0.0)) {
    return 0.0;
  }
  // Vose: scaled weights n w_i / sum, mean 1. `work` holds the small ones
  // from the front and the large ones from the back; the scaled values live
  // in float64 in a local copy so the pairing does not drift.
  work.resize(n);
  std::vector<double> scaled(n);
  std::size_t small = 0, large = n;
  const double to_scaled = static_cast<double>(n) / sum;
  for (std::size_t i = 0; i < n; ++i) {
    scaled[i] = (weights[i] > 0.0f ? weights[i] : 0.0f) * to_scaled;
    if (scaled[i] < 1.0)
      work[small++] = static_cast<std::uint32_t>(i);
    else
      work[--large] = static_cast<std::uint32_t>(i);
  }
  // Pair the last small with the last large; the large's remainder goes back
  // to whichever list it now belongs to.
  std::size_t small_end = small;
  while (small_end > 0 && large < n) {
    const std::uint32_t s = work[--small_end];
    const std::uint32_t l = work[large];
    table[s] = {static_cast<float>(scaled[s]), l};
    scaled[l] = (scaled[l] + scaled[s]) - 1.0;
    if (scaled[l] < 1.0) {
      ++large;
      work[small_end++] = l;
    }
  }
  // What is left is 1 up to rounding.
  while (large < n) table[work[large++]].probability = 1.0f;
  while (small_end > 0) table[work[--small_end]].probability = 1.0f;
  return sum;
}

AliasTables build_alias_tables(const float* matrix, std::size_t rows, std::size_t cols,
                               Progress* progress) {
  if (cols > std::numeric_limits<std::uint32_t>::max())
    throw Error("alias tables", std::to_string(cols) + " columns exceed 32-bit indices");
  AliasTables t;
  t.rows = rows;
  t.cols = cols;
  t.entries.resize(rows * cols);
  t.row_sum.resize(rows);
  if (progress) progress->begin_stage("alias tables", rows);
  const auto count = static_cast<std::ptrdiff_t>(rows);
#pragma omp parallel
  {
    std::vector<std::uint32_t> work;
#pragma omp for schedule(dynamic, 16)
    for (std::ptrdiff_t r = 0; r < count; ++r) {
      if (progress && progress->should_stop()) continue;
      const auto row = static_cast<std::size_t>(r);
      t.row_sum[row] = static_cast<float>(
          build_alias_row(matrix + row * cols, cols, t.entries.data() + row * cols, work));
      if (progress) progress->advance();
    }
  }
  if (progress) {
    progress->check();
    progress->end_stage();
  }
  return t;
}

}  // namespace bounce
