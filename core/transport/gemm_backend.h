#pragma once
// One dense product C = A B + beta C on n x n row-major float32 matrices held
// on the host. Everything the transport stage multiplies goes through this
// interface, so OpenBLAS and CLBlast are interchangeable and testable against
// each other. c must not alias a or b.
#include <cstddef>
#include <string>

namespace bounce {

class GemmBackend {
 public:
  virtual ~GemmBackend() = default;
  // "OpenBLAS" or "CLBlast (<device>)".
  virtual std::string name() const = 0;
  virtual void multiply(std::size_t n, const float* a, const float* b, float beta, float* c) = 0;
};

// Floating-point operations of one n x n x n product (2 n^3).
inline double gemm_flops(std::size_t n) {
  const double d = static_cast<double>(n);
  return 2.0 * d * d * d;
}

}  // namespace bounce
