#include "transport_bench.h"

#include <algorithm>
#include <chrono>
#include <random>

#include "transport/blas_kernels.h"
#include "transport/clblast_gemm.h"
#include "transport/inverse_transport.h"
#include "transport/openblas_gemm.h"
#include "transport/plain_gemm.h"
#include "transport/text_format.h"

namespace bounce {

namespace {

// A balanced M = diag(rho) A^-1 G (G symmetric, rows of F summing to at most
// 0.9), as a bake's K = infinity solves: both methods get the same matrix.
struct BalancedM {
  std::vector<float> m, area, albedo;
};

BalancedM balanced_m(std::size_t n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  BalancedM b;
  b.area.resize(n);
  b.albedo.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    b.area[p] = 0.5f + u(rng);
    b.albedo[p] = 0.3f + 0.6f * u(rng);
  }
  b.m.resize(n * n);
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t q = p; q < n; ++q) b.m[p * n + q] = b.m[q * n + p] = u(rng);
  double worst = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    double row = 0.0;
    for (std::size_t q = 0; q < n; ++q) row += b.m[p * n + q];
    worst = std::max(worst, row / b.area[p]);
  }
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t q = 0; q < n; ++q)
      b.m[p * n + q] = static_cast<float>(b.albedo[p] * 0.9 / worst * b.m[p * n + q] / b.area[p]);
  return b;
}

BenchEntry time_solve(const BalancedM& b, std::size_t n, int repeats, InverseMethod method,
                      TransportPrecision precision) {
  BenchEntry e;
  e.what = std::string(method_name(method)) + " " + precision_name(precision) + " (K = infinity)";
  InverseOptions options;
  options.force = precision;
  if (method == InverseMethod::Cholesky) {
    options.area = b.area;
    options.albedo = b.albedo;
  }
  std::vector<double> seconds;
  double flops = 0.0;
  for (int i = 0; i < repeats; ++i) {
    const auto start = std::chrono::steady_clock::now();
    flops = solve_infinite_bounces(b.m, n, -1.0, options).flops;
    seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  e.timing.n = n;
  e.timing.repeats = repeats;
  e.timing.best_seconds = seconds.front();
  e.timing.median_seconds = seconds[seconds.size() / 2];
  e.timing.gflops = flops / e.timing.best_seconds * 1e-9;
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
    b.entries.push_back({"OpenBLAS sgemm (" + choose_blas_kernels().used + ")",
                         true,
                         {},
                         time_gemm(openblas, n, b.repeats)});
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
    const BalancedM m = balanced_m(n);
    for (const InverseMethod method : {InverseMethod::Cholesky, InverseMethod::LU})
      for (const TransportPrecision p : {TransportPrecision::Float32, TransportPrecision::Float64})
        b.entries.push_back(time_solve(m, n, b.repeats, method, p));
  }
  return b;
}

}  // namespace bounce
