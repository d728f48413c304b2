#pragma once
// How fast the run-time product indirect_k = T_c(k) b_k is on this machine
// (for `bounce bench runtime`): the compressed matrix on OpenCL and in C++,
// and the dense float32 matrices with OpenBLAS, measured back to back in one
// process, next to the machine's own read bandwidth measured in the same run
// (timings swing by tens of percent between runs here: compare within one).
// The dense product streams its matrices and is bandwidth-bound; the bytes
// each path reads per update, over its time, say how close it gets.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "compress/codec.h"
#include "runtime/classic_radiosity.h"
#include "runtime/final_gather.h"

namespace bounce {

struct RuntimeBenchEntry {
  std::string what;           // "compressed, OpenCL (<device>)", "compressed, C++ (avx2)", ...
  bool available = true;      // false: could not run, `error` says why
  bool default_loop = false;  // the C++ loop `bounce solve` runs (BlockLoop::kFastest)
  std::string error;
  double best_ms = 0.0, median_ms = 0.0;  // per update
  std::size_t bytes = 0;                  // read per update
  double gb_per_s = 0.0;                  // bytes / best time
  // max_p,k |y - y_cpp| / max_p,k |y_cpp| against the compressed C++ path's
  // float32 result: float rounding for the OpenCL path, bfloat16 rounding
  // for the bfloat16 loop; for the dense path, the error compression itself
  // adds to the indirect light (the matrices given are the exact ones).
  double max_rel_diff = 0.0;
};

struct RuntimeBench {
  std::size_t n = 0;
  int channels = 0;             // stored channels
  std::string format;           // "BC1" / "BC4"
  std::size_t corrections = 0;  // kept positions (union over stored channels)
  int repeats = 0;
  double stream_gb_per_s = 0.0;            // measure_read_bandwidth() of this run
  std::vector<RuntimeBenchEntry> entries;  // OpenCL, C++, dense (if given)
  // The final gather from the patches' light to the lit mesh's vertices,
  // the other half of a light update (available: the bake has one); its
  // rel diff is against a double-precision sum of the same rows.
  RuntimeBenchEntry gather;
  std::size_t gather_points = 0, gather_entries = 0;
  bool gather_compact = false;  // the rows in 4-byte entries (FinalGather::compact)
  // Compact rows: the gather again with each loop this CPU has (default_loop:
  // the one FinalGather::compact_rows() timed fastest and the product runs).
  std::vector<RuntimeBenchEntry> gather_loops;
};

// Each path: one warm-up, then `repeats` timed products of the same random
// b (best and median). `dense`: the exact matrices, one per stored channel
// (n x n, row-major, patch order); empty: no dense entry. The OpenCL entry is
// marked unavailable (with the reason) when OpenCL has no device.
// `classic`: the K-iteration baseline on the form factors (nullptr: none);
// its max_rel_diff against the compressed product includes both the
// compression error and any difference of K. `gather`: the bake's final
// gather (nullptr: none), timed on the same patch light.
RuntimeBench run_runtime_bench(const CompressedMatrix& m, const std::array<int, 3>& channel_of_rgb,
                               const std::vector<const float*>& dense, int repeats,
                               const ClassicRadiosity* classic = nullptr,
                               const FinalGather* gather = nullptr);

// Read bandwidth in GB/s (1e9 bytes): the best of `repeats` sums over a float
// array of `bytes`, on all OpenMP threads (a STREAM-like read-only test).
double measure_read_bandwidth(std::size_t bytes = std::size_t{512} << 20, int repeats = 5);

// The result as a text table (one line per path, then the bandwidth).
std::string runtime_bench_table(const RuntimeBench& bench);

}  // namespace bounce
