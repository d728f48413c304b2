#include "compress/sparse_split.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>

namespace bounce {

namespace {

std::vector<std::uint32_t> every_row(std::size_t n) {
  std::vector<std::uint32_t> rows(n);
  for (std::size_t i = 0; i < n; ++i) rows[i] = static_cast<std::uint32_t>(i);
  return rows;
}

// Positive floats order as their bit patterns, so the k-th largest entry is
// found by two counting passes, over the high and then the low 16 bits of
// the patterns, each in parallel: the value nth_element gives, without a
// copy of the matrix or a serial selection (the selection took 0.3-0.7 s per
// channel of the Cornell box's 4348 x 4348, each time the budget's search
// split the matrix).
using Histogram = std::vector<std::uint64_t>;
constexpr std::size_t kBins = std::size_t{1} << 16;

// Counts of the positive entries of `rows` by the high half of their bits;
// with `high`, counts by the low half of those whose high half it is.
Histogram count_bit_halves(const float* matrix, std::size_t n, std::span<const std::uint32_t> rows,
                           std::optional<std::uint32_t> high) {
  Histogram total(kBins, 0);
#pragma omp parallel
  {
    Histogram local(kBins, 0);
#pragma omp for schedule(static) nowait
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const float* row = matrix + std::size_t{rows[r]} * n;
      for (std::size_t j = 0; j < n; ++j) {
        if (!(row[j] > 0.0f)) continue;
        const auto bits = std::bit_cast<std::uint32_t>(row[j]);
        if (!high)
          ++local[bits >> 16];
        else if (bits >> 16 == *high)
          ++local[bits & 0xffffu];
      }
    }
#pragma omp critical
    for (std::size_t b = 0; b < kBins; ++b) total[b] += local[b];
  }
  return total;
}

// The bin holding the rank-th largest entry (rank from 1; at most the
// histogram's total) and its rank within that bin.
std::pair<std::uint32_t, std::uint64_t> bin_of_rank(const Histogram& h, std::uint64_t rank) {
  for (std::size_t b = kBins; b-- > 1;) {
    if (rank <= h[b]) return {static_cast<std::uint32_t>(b), rank};
    rank -= h[b];
  }
  return {0, rank};
}

}  // namespace

float kept_threshold(const float* matrix, std::size_t n, double fraction) {
  return kept_threshold(matrix, n, every_row(n), fraction);
}

CsrMatrix extract_kept(const float* matrix, std::size_t n, float threshold, const float* key) {
  return extract_kept(matrix, n, threshold, key, every_row(n));
}

float kept_threshold(const float* matrix, std::size_t n, std::span<const std::uint32_t> rows,
                     double fraction) {
  const std::size_t total = rows.size() * n;
  const auto keep = static_cast<std::uint64_t>(std::llround(fraction * static_cast<double>(total)));
  if (keep == 0) return std::numeric_limits<float>::infinity();
  const Histogram high = count_bit_halves(matrix, n, rows, std::nullopt);
  std::uint64_t positive = 0;
  for (const std::uint64_t c : high) positive += c;
  if (keep >= positive) return std::numeric_limits<float>::min();
  // The keep-th largest: its high half, then its low half among those.
  const auto [high_half, rank] = bin_of_rank(high, keep);
  const Histogram low = count_bit_halves(matrix, n, rows, high_half);
  const std::uint32_t low_half = bin_of_rank(low, rank).first;
  return std::bit_cast<float>(high_half << 16 | low_half);
}

CsrMatrix extract_kept(const float* matrix, std::size_t n, float threshold, const float* key,
                       std::span<const std::uint32_t> rows) {
  if (!key) key = matrix;
  // With a key of its own, an entry that is zero may be kept too: a zero the
  // blocks decode as non-zero is an error like any other.
  const auto kept = [&](std::size_t k) { return key[k] >= threshold && key[k] > 0.0f; };
  // Counted per row, then written per row, both in parallel.
  std::vector<std::uint32_t> count(n, 0);
#pragma omp parallel for schedule(static)
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const std::size_t i = rows[r];
    std::uint32_t c = 0;
    for (std::size_t j = 0; j < n; ++j) c += kept(i * n + j) ? 1u : 0u;
    count[i] = c;
  }
  CsrMatrix m;
  m.n = n;
  m.row_ptr.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) m.row_ptr[i + 1] = m.row_ptr[i] + count[i];
  m.col.resize(m.row_ptr[n]);
  m.value.resize(m.row_ptr[n]);
#pragma omp parallel for schedule(static)
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const std::size_t i = rows[r];
    std::size_t at = m.row_ptr[i];
    for (std::size_t j = 0; j < n; ++j)
      if (kept(i * n + j)) {
        m.col[at] = static_cast<std::uint32_t>(j);
        m.value[at++] = matrix[i * n + j];
      }
  }
  return m;
}

}  // namespace bounce
