#pragma once
// OpenBLAS picks its kernels from the CPU's model number. A release older
// than the CPU does not know the model and falls back to its SSE3 kernels
// ("Prescott"): Debian 12's OpenBLAS 0.3.21 on an Intel Xeon of model 207
// ran sgemm at 38 GFLOP/s on 2 cores, where its AVX-512 kernels ("SkylakeX")
// reach 225. The transport's Cholesky and inverse run on those kernels, so
// that fallback made the Cornell box's transport stage three times as long.
//
// choose_blas_kernels() corrects that fallback by measurement: when OpenBLAS
// chose kernels older than AVX on a CPU that has AVX, it times a small sgemm
// on OpenBLAS's choice and on the kernels the CPU's instruction sets allow
// (AVX-512 -> SkylakeX, AVX2 + FMA -> Haswell, AVX -> Sandybridge), and keeps
// the faster. Each is timed on one thread in that thread's CPU time, so that
// a loaded machine does not change the choice (the kernels round
// differently, and two bakes of one scene should give the same bytes).
// Anything else is left as OpenBLAS chose it: a CPU it knows, an
// OPENBLAS_CORETYPE the user set, or an OpenBLAS built for one CPU.
#include <shared_mutex>
#include <string>

namespace bounce {

struct BlasKernels {
  std::string detected;   // OpenBLAS's own choice ("" when it does not say)
  std::string used;       // what runs now
  std::string why;        // one line: why `used`
  std::string candidate;  // the kernels tried against `detected` ("" when none were)
  // One thread's sgemm GFLOP/s of each, measured on n = kProbeSize; 0 when
  // not measured.
  double detected_gflops = 0.0, candidate_gflops = 0.0;
  static constexpr int kProbeSize = 384;
};

// Decides once per process (later calls return the first decision) and
// returns the decision. Call it before BLAS runs on another thread: it
// re-initialises OpenBLAS's kernel table. The bake, the runtime's dense
// product and the front ends' start call it.
const BlasKernels& choose_blas_kernels();

// Held shared by the runtime's dense product (dense_indirect, which the
// studio runs on its preview and view jobs while a bake runs on another
// thread), and exclusively while OpenBLAS's kernel table is switched or its
// worker threads are restarted (transport/flush_subnormals.h): a restart
// while another thread's product is on those workers would leave that
// product waiting forever.
std::shared_mutex& blas_threads_mutex();

}  // namespace bounce
