#include "transport/plain_gemm.h"

#include <cstdint>

namespace bounce {

void PlainGemm::multiply(std::size_t n, const float* a, const float* b, float beta, float* c) {
  // A signed loop index: OpenMP's worksharing loop wants one on older GCCs,
  // and n fits (the matrix has n^2 entries in memory).
  const auto rows = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t r = 0; r < rows; ++r) {
    const auto i = static_cast<std::size_t>(r);
    float* ci = c + i * n;
    // BLAS semantics: beta = 0 overwrites C, so NaN or garbage in C does not
    // leak into the result.
    if (beta == 0.0f) {
      for (std::size_t j = 0; j < n; ++j) ci[j] = 0.0f;
    } else if (beta != 1.0f) {
      for (std::size_t j = 0; j < n; ++j) ci[j] *= beta;
    }
    const float* ai = a + i * n;
    for (std::size_t k = 0; k < n; ++k) {
      const float aik = ai[k];
      const float* bk = b + k * n;
      for (std::size_t j = 0; j < n; ++j) ci[j] += aik * bk[j];
    }
  }
}

}  // namespace bounce
