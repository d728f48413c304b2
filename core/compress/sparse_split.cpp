#include "compress/sparse_split.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bounce {

float kept_threshold(const float* matrix, std::size_t n, double fraction) {
  const std::size_t total = n * n;
  const auto keep = static_cast<std::size_t>(std::llround(fraction * static_cast<double>(total)));
  if (keep == 0) return std::numeric_limits<float>::infinity();
  std::vector<float> positive;
  positive.reserve(total);
  for (std::size_t k = 0; k < total; ++k)
    if (matrix[k] > 0.0f) positive.push_back(matrix[k]);
  if (keep >= positive.size()) return std::numeric_limits<float>::min();
  // The keep-th largest value.
  std::nth_element(positive.begin(), positive.begin() + static_cast<std::ptrdiff_t>(keep - 1),
                   positive.end(), std::greater<float>());
  return positive[keep - 1];
}

CsrMatrix extract_kept(const float* matrix, std::size_t n, float threshold, const float* key) {
  if (!key) key = matrix;
  CsrMatrix m;
  m.n = n;
  m.row_ptr.reserve(n + 1);
  m.row_ptr.push_back(0);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      const float v = matrix[i * n + j];
      // With a key of its own, an entry that is zero may be kept too: a
      // zero the blocks decode as non-zero is an error like any other.
      if (key[i * n + j] >= threshold && key[i * n + j] > 0.0f) {
        m.col.push_back(static_cast<std::uint32_t>(j));
        m.value.push_back(v);
      }
    }
    m.row_ptr.push_back(static_cast<std::uint32_t>(m.col.size()));
  }
  return m;
}

}  // namespace bounce
