#pragma once
// Timing one n x n product on a backend: used by Backend::Auto to pick the
// faster backend and by `bounce bench transport`. Dense timings swing +-30%
// run to run on these machines, so the best of `repeats` runs is the figure to
// compare, measured back to back in one process.
#include <cstddef>

#include "transport/gemm_backend.h"

namespace bounce {

struct GemmTiming {
  std::size_t n = 0;
  int repeats = 0;
  double best_seconds = 0.0;
  double median_seconds = 0.0;
  double gflops = 0.0;  // 2 n^3 / best_seconds / 1e9
};

// Runs `warmups` untimed products first (CLBlast compiles its kernels on the
// first call), then `repeats` timed ones on non-negative random matrices.
GemmTiming time_gemm(GemmBackend& backend, std::size_t n, int repeats, int warmups = 1);

}  // namespace bounce
