#pragma once
// GemmBackend on OpenBLAS's cblas_sgemm (the CPU reference backend: always
// available, and the fallback when OpenCL is not).
#include "transport/gemm_backend.h"

namespace bounce {

class OpenBlasGemm final : public GemmBackend {
 public:
  std::string name() const override { return "OpenBLAS"; }
  void multiply(std::size_t n, const float* a, const float* b, float beta, float* c) override;
};

}  // namespace bounce
