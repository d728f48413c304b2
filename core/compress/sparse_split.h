#pragma once
// The exact part of the compressed matrix: the largest entries of a channel,
// kept as float32 in CSR form and removed ("holes") from the dense remainder
// that is log-quantised and block-compressed.
#include <cstdint>
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

}  // namespace bounce
