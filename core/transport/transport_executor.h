#pragma once
// Where the multi-bounce products and the K = infinity solve run when not in
// this process. compute_transport keeps every decision (channels, K, scheme,
// precision rule) and hands only the dense algebra to the executor, so a
// distributed run decides exactly as a single process does. The one
// implementation is core/distributed (ScaLAPACK over MPI ranks); without an
// executor compute_transport uses OpenBLAS/CLBlast and LAPACKE here.
#include <cstddef>
#include <string>
#include <vector>

#include "transport/gemm_backend.h"
#include "transport/inverse_transport.h"

namespace bounce {

class TransportExecutor {
 public:
  virtual ~TransportExecutor() = default;
  // The product backend every series product goes through.
  virtual GemmBackend& gemm() = 0;
  // What solve_infinite_bounces does (same precision rule, same layout of m
  // and of the result), on the executor's machinery.
  virtual InverseTransport solve_infinite(std::vector<float> m, std::size_t n,
                                          double spectral_radius,
                                          const InverseOptions& options) = 0;
  // One line for the manifest's decisions: where the algebra ran and why.
  virtual std::string description() const = 0;
};

}  // namespace bounce
