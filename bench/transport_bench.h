#pragma once
// `bounce bench transport`: how fast the two GEMM backends and the two LU
// precisions are on this machine, measured back to back in one process (dense
// timings swing +-30% between runs here; compare ratios within one run), with
// an unblocked triple loop (transport/plain_gemm.h) as the naive baseline.
#include <cstddef>
#include <string>
#include <vector>

#include "transport/gemm_timing.h"

namespace bounce {

struct BenchEntry {
  std::string what;       // "OpenBLAS sgemm", "CLBlast sgemm (<device>)", "LU float32", ...
  bool available = true;  // false: could not run, `error` says why
  std::string error;
  GemmTiming timing;  // for a solve: all of (I - M) T = M; gflops counts the flops it reports
};

struct TransportBench {
  std::size_t n = 0;
  int repeats = 0;
  std::vector<BenchEntry> entries;
};

// The plain loop is timed up to this size only: beyond it one product takes
// tens of seconds and more (about 2 s at 2048 here, 8x per doubling) and
// says nothing the smaller sizes do not.
inline constexpr std::size_t kPlainGemmMaxN = 2048;

// One n x n sgemm on OpenBLAS and on CLBlast (best and median of `repeats`
// after one warm-up); with `with_lu`, also the K = infinity solve by
// Cholesky and by LU in float32 and float64 on one random balanced M
// (A F symmetric, rows of F summing to at most 0.9); with
// `with_plain`, also the plain loop: `repeats` runs after a warm-up below
// n = kPlainGemmMaxN, one run without warm-up at it, skipped (available =
// false, with the reason) above it.
TransportBench run_transport_bench(std::size_t n, int repeats, bool with_lu = false,
                                   bool with_plain = false);

// One n x n OpenBLAS sgemm, best of `repeats` after a warm-up: the machine's
// dense float32 rate, which `bench bake` sets the transport stage against.
GemmTiming time_openblas_sgemm(std::size_t n, int repeats);

}  // namespace bounce
