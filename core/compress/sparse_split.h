#pragma once
// The exact part of the compressed matrix: the largest entries of a channel,
// kept as float32 in CSR form and removed ("holes") from the dense remainder
// that is log-quantised and block-compressed.
#include <cstdint>
#include <span>
#include <vector>

namespace bounce {

struct CsrMatrix {
  std::size_t n = 0;
  std::vector<std::uint32_t> row_ptr;  // n + 1
  std::vector<std::uint32_t> col;
  std::vector<float> value;
  std::size_t bytes() const {
    return row_ptr.size() * sizeof(std::uint32_t) + col.size() * sizeof(std::uint32_t) +
           value.size() * sizeof(float);
  }
};

// Value above which entries are kept: the (1 - fraction) quantile of the
// channel's positive entries (ties kept too). fraction in [0, 1]. `matrix`
// may be any n x n key that decides what is kept (see extract_kept).
float kept_threshold(const float* matrix, std::size_t n, double fraction);

// Entries >= threshold (and > 0) in CSR form; with `key` (n x n), the entries
// whose key is >= threshold and > 0, zeros of the matrix included.
CsrMatrix extract_kept(const float* matrix, std::size_t n, float threshold,
                       const float* key = nullptr);

// The same over the rows `rows` of the matrix only (ascending patch indices):
// the threshold keeps `fraction` of their n entries each, and the CSR holds
// those rows' kept entries (every other row empty). With every row, the same
// threshold and entries as above. The error budget's search splits a sample
// of the rows this way.
float kept_threshold(const float* matrix, std::size_t n, std::span<const std::uint32_t> rows,
                     double fraction);
CsrMatrix extract_kept(const float* matrix, std::size_t n, float threshold, const float* key,
                       std::span<const std::uint32_t> rows);

}  // namespace bounce
