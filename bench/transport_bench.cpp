#include "transport_bench.h"

#include <algorithm>
#include <chrono>
#include <random>

#include "transport/clblast_gemm.h"
#include "transport/inverse_transport.h"
#include "transport/openblas_gemm.h"
#include "transport/plain_gemm.h"
#include "transport/text_format.h"

namespace bounce {

namespace {

BenchEntry time_solve(std::size_t n, int repeats, TransportPrecision precision) {
  BenchEntry e;
  e.what = std::string("LU ") + precision_name(precision) + " (K = infinity)";
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> m(n * n);
  for (std::size_t p = 0; p < n; ++p) {
    float sum = 0.0f;
    for (std::size_t q = 0; q < n; ++q) sum += m[p * n + q] = u(rng);
    for (std::size_t q = 0; q < n; ++q) m[p * n + q] *= 0.9f / sum;
  }
  InverseOptions options;
  options.force = precision;
  std::vector<double> seconds;
  for (int i = 0; i < repeats; ++i) {
    const auto start = std::chrono::steady_clock::now();
    solve_infinite_bounces(m, n, 0.9, options);
    seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  const double d = static_cast<double>(n);
  e.timing.n = n;
  e.timing.repeats = repeats;
  e.timing.best_seconds = seconds.front();
  e.timing.median_seconds = seconds[seconds.size() / 2];
  e.timing.gflops = (2.0 + 2.0 / 3.0) * d * d * d / e.timing.best_seconds * 1e-9;
  return e;
}

BenchEntry time_plain(std::size_t n, int repeats) {
  const std::string what = "plain sgemm (i-k-j loop, OpenMP)";
  if (n > kPlainGemmMaxN)
    return {what,
            false,
            text_format("skipped above n = %zu: its time grows as n^3 (8x per doubling of n, "
                        "tens of seconds and more per product) and the sizes up to %zu already "
                        "show its ratio to OpenBLAS",
                        kPlainGemmMaxN, kPlainGemmMaxN),
            {}};
  PlainGemm plain;
  // At the largest size one product already takes seconds; a warm-up and
  // repeats would only multiply that.
  const bool once = n >= kPlainGemmMaxN;
  return {what, true, {}, time_gemm(plain, n, once ? 1 : repeats, once ? 0 : 1)};
}

}  // namespace

GemmTiming time_openblas_sgemm(std::size_t n, int repeats) {
  OpenBlasGemm openblas;
  return time_gemm(openblas, n, repeats);
}

TransportBench run_transport_bench(std::size_t n, int repeats, bool with_lu, bool with_plain) {
  TransportBench b;
  b.n = n;
  b.repeats = std::max(repeats, 1);
  {
    OpenBlasGemm openblas;
    b.entries.push_back({"OpenBLAS sgemm", true, {}, time_gemm(openblas, n, b.repeats)});
  }
  try {
    ClblastGemm clblast;
    b.entries.push_back(
        {"CLBlast sgemm on " + clblast.device_name(), true, {}, time_gemm(clblast, n, b.repeats)});
  } catch (const Error& e) {
    b.entries.push_back({"CLBlast sgemm", false, e.what(), {}});
  }
  if (with_plain) b.entries.push_back(time_plain(n, b.repeats));
  if (with_lu) {
    b.entries.push_back(time_solve(n, b.repeats, TransportPrecision::Float32));
    b.entries.push_back(time_solve(n, b.repeats, TransportPrecision::Float64));
  }
  return b;
}

}  // namespace bounce
