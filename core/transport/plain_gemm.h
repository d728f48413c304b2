#pragma once
// GemmBackend on a straightforward triple loop: the baseline that shows what
// OpenBLAS and CLBlast buy (`bounce bench transport`). Rows of C are shared
// among OpenMP threads; each row is C[i][:] = beta C[i][:] + sum_k A[i][k] B[k][:]
// in i-k-j order (the innermost loop walks B and C contiguously, so the
// compiler vectorises it), with no blocking for the caches and no packing: B
// is streamed from memory once per row of C once it no longer fits in cache.
// Not for production use: it is several times slower than OpenBLAS at
// n >= 1024.
#include "transport/gemm_backend.h"

namespace bounce {

class PlainGemm final : public GemmBackend {
 public:
  std::string name() const override { return "plain i-k-j loop"; }
  void multiply(std::size_t n, const float* a, const float* b, float beta, float* c) override;
};

}  // namespace bounce
