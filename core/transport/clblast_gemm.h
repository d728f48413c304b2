#pragma once
// GemmBackend on CLBlast over OpenCL. There is no GPU on the machines this is
// built on: PoCL's CPU device runs it, so this path is always exercised.
// Matrices stay on the host between calls; each product uploads A and B (and C
// when beta != 0) and reads C back. On a CPU device that is three memcpys per
// 2 n^3 flops; on a discrete GPU it is bus traffic that a resident-buffer
// interface would avoid -- the bench reports the time including it.
#include <memory>
#include <string>

#include "base/error.h"
#include "compute/opencl_error.h"
#include "transport/gemm_backend.h"

namespace bounce {

class ClblastGemm final : public GemmBackend {
 public:
  // Opens the process-wide OpenCL device: the first GPU if there is one, else
  // the first device of any kind (PoCL's CPU device here). Throws OpenClError
  // when OpenCL has no platform or device.
  ClblastGemm();
  ~ClblastGemm() override;
  ClblastGemm(const ClblastGemm&) = delete;
  ClblastGemm& operator=(const ClblastGemm&) = delete;

  std::string name() const override;
  void multiply(std::size_t n, const float* a, const float* b, float beta, float* c) override;
  const std::string& device_name() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bounce
