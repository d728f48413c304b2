#include "compress/sparse_split.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bounce {

namespace {

std::vector<std::uint32_t> every_row(std::size_t n) {
  std::vector<std::uint32_t> rows(n);
  for (std::size_t i = 0; i < n; ++i) rows[i] = static_cast<std::uint32_t>(i);
  return rows;
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
  const auto keep = static_cast<std::size_t>(std::llround(fraction * static_cast<double>(total)));
  if (keep == 0) return std::numeric_limits<float>::infinity();
  std::vector<float> positive;
  positive.reserve(total);
  for (std::uint32_t i : rows)
    for (std::size_t j = 0; j < n; ++j)
      if (matrix[i * n + j] > 0.0f) positive.push_back(matrix[i * n + j]);
  if (keep >= positive.size()) return std::numeric_limits<float>::min();
  // The keep-th largest value.
  std::nth_element(positive.begin(), positive.begin() + static_cast<std::ptrdiff_t>(keep - 1),
                   positive.end(), std::greater<float>());
  return positive[keep - 1];
}

CsrMatrix extract_kept(const float* matrix, std::size_t n, float threshold, const float* key,
                       std::span<const std::uint32_t> rows) {
  if (!key) key = matrix;
  CsrMatrix m;
  m.n = n;
  m.row_ptr.reserve(n + 1);
  m.row_ptr.push_back(0);
  std::size_t next = 0;  // the next row of `rows`
  for (std::size_t i = 0; i < n; ++i) {
    if (next < rows.size() && rows[next] == i) {
      ++next;
      for (std::size_t j = 0; j < n; ++j) {
        const float v = matrix[i * n + j];
        // With a key of its own, an entry that is zero may be kept too: a
        // zero the blocks decode as non-zero is an error like any other.
        if (key[i * n + j] >= threshold && key[i * n + j] > 0.0f) {
          m.col.push_back(static_cast<std::uint32_t>(j));
          m.value.push_back(v);
        }
      }
    }
    m.row_ptr.push_back(static_cast<std::uint32_t>(m.col.size()));
  }
  return m;
}

}  // namespace bounce
