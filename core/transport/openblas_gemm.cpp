#include "transport/openblas_gemm.h"

#include <cblas.h>

#include "transport/blas_int.h"

static_assert(sizeof(blasint) == sizeof(int), "OpenBLAS built with 64-bit integers");

namespace bounce {

void OpenBlasGemm::multiply(std::size_t n, const float* a, const float* b, float beta, float* c) {
  if (n == 0) return;
  const int k = blas_dim(n, "cblas_sgemm");
  cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasNoTrans, k, k, k, 1.0f, a, k, b, k, beta, c, k);
}

}  // namespace bounce
