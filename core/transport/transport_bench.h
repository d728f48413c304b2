#pragma once
// `bounce bench transport`: how fast the two GEMM backends and the two LU
// precisions are on this machine, measured back to back in one process (dense
// timings swing +-30% between runs here; compare ratios within one run).
#include <cstddef>
#include <string>
#include <vector>

#include "transport/gemm_timing.h"

namespace bounce {

struct BenchEntry {
  std::string what;       // "OpenBLAS sgemm", "CLBlast sgemm (<device>)", "LU float32", ...
  bool available = true;  // false: could not run, `error` says why
  std::string error;
  GemmTiming timing;  // for LU: the full solve of (I - M) T = M; gflops counts 2 n^3 + 2/3 n^3
};

struct TransportBench {
  std::size_t n = 0;
  int repeats = 0;
  std::vector<BenchEntry> entries;
};

// One n x n sgemm on OpenBLAS and on CLBlast (best and median of `repeats`
// after one warm-up); with `with_lu`, also the K = infinity solve in float32
// and float64 on a random substochastic M (rows summing to 0.9).
TransportBench run_transport_bench(std::size_t n, int repeats, bool with_lu = false);

}  // namespace bounce
