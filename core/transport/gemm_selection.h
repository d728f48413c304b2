#pragma once
// Picks the GEMM backend for a transport run. Backend::Auto times one product
// on OpenBLAS and on CLBlast (at min(n, 512), once per process and size: the
// answer does not change within a run, and CLBlast's first call compiles its
// kernels) and keeps the faster -- unless OpenBLAS alone is predicted to do
// all `gemms` products in less than settings.auto_probe_min_seconds, where
// probing would cost more than it could save. Whenever CLBlast cannot be used -- no OpenCL
// device, or a failure, even in the middle of a run -- OpenBLAS takes over and
// a warning says why. Every choice is recorded with its measurements.
#include <cstddef>
#include <memory>
#include <vector>

#include "base/diagnostics.h"
#include "transport/gemm_backend.h"
#include "transport/transport_decision.h"
#include "transport/transport_settings.h"

namespace bounce {

struct GemmSelection {
  std::unique_ptr<GemmBackend> backend;
  // The Auto probe's timings (best of 3, seconds); 0 when not measured.
  std::size_t probe_n = 0;
  double openblas_seconds = 0.0;
  double clblast_seconds = 0.0;
};

GemmSelection select_gemm_backend(const TransportSettings& settings, std::size_t n,
                                  std::size_t gemms, Diagnostics& diagnostics,
                                  std::vector<TransportDecision>& decisions);

}  // namespace bounce
