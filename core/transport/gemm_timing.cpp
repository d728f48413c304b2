#include "transport/gemm_timing.h"

#include <algorithm>
#include <chrono>
#include <random>
#include <vector>

namespace bounce {

GemmTiming time_gemm(GemmBackend& backend, std::size_t n, int repeats, int warmups) {
  GemmTiming t;
  t.n = n;
  t.repeats = std::max(repeats, 1);
  // Entries like a transport matrix's: non-negative, rows summing below 1, so
  // the products stay finite and denormal-free whatever the size.
  std::mt19937 rng(12345);
  std::uniform_real_distribution<float> u(0.0f, 1.0f / static_cast<float>(std::max<std::size_t>(n, 1)));
  std::vector<float> a(n * n), b(n * n), c(n * n, 0.0f);
  for (float& x : a) x = u(rng);
  for (float& x : b) x = u(rng);
  for (int i = 0; i < warmups; ++i) backend.multiply(n, a.data(), b.data(), 0.0f, c.data());
  std::vector<double> seconds;
  for (int i = 0; i < t.repeats; ++i) {
    const auto start = std::chrono::steady_clock::now();
    backend.multiply(n, a.data(), b.data(), 0.0f, c.data());
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  t.best_seconds = seconds.front();
  t.median_seconds = seconds[seconds.size() / 2];
  t.gflops = t.best_seconds > 0.0 ? gemm_flops(n) / t.best_seconds * 1e-9 : 0.0;
  return t;
}

}  // namespace bounce
