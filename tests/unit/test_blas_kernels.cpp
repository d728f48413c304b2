// The BLAS kernel choice: it reports what OpenBLAS runs, keeps the faster of
// the kernels it measured, and the kernels it leaves in place compute the
// same products as a plain loop (a kernel table re-initialised wrongly would
// not).
#include <gtest/gtest.h>

#include <cblas.h>
#include <strings.h>

#include <cmath>
#include <random>
#include <vector>

#include "transport/blas_kernels.h"

namespace bounce {

namespace {

TEST(BlasKernels, ReportsTheKernelsOpenBlasRuns) {
  const BlasKernels& k = choose_blas_kernels();
  EXPECT_EQ(&k, &choose_blas_kernels()) << "decided once per process";
  ASSERT_NE(openblas_get_corename(), nullptr);
  EXPECT_EQ(strcasecmp(k.used.c_str(), openblas_get_corename()), 0)
      << k.used << " vs " << openblas_get_corename();
  EXPECT_FALSE(k.why.empty());
  if (k.candidate.empty()) {
    EXPECT_EQ(k.used, k.detected);
    return;
  }
  ASSERT_GT(k.detected_gflops, 0.0);
  ASSERT_GT(k.candidate_gflops, 0.0);
  EXPECT_EQ(k.used, k.candidate_gflops > k.detected_gflops ? k.candidate : k.detected) << k.why;
}

TEST(BlasKernels, ChosenKernelsMultiplyAsAPlainLoopDoes) {
  choose_blas_kernels();
  // Large enough for OpenBLAS's blocked, threaded path; odd to reach its edges.
  constexpr int n = 517;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> a(std::size_t{n} * n), b(a.size()), c(a.size());
  for (float& v : a) v = u(rng);
  for (float& v : b) v = u(rng);
  cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasNoTrans, n, n, n, 1.0f, a.data(), n, b.data(), n,
              0.0f, c.data(), n);
  double worst = 0.0;
  for (int i = 0; i < n; i += 7)
    for (int j = 0; j < n; ++j) {
      double exact = 0.0, size = 0.0;
      for (int k = 0; k < n; ++k) {
        exact += double{a[i * n + k]} * b[k * n + j];
        size += std::abs(double{a[i * n + k]} * b[k * n + j]);
      }
      worst = std::max(worst, std::abs(c[i * n + j] - exact) / size);
    }
  // float32 sums of n terms: at most about n * 2^-24 of the terms' sizes.
  EXPECT_LT(worst, n * std::ldexp(1.0, -24)) << choose_blas_kernels().used;
}

}  // namespace

}  // namespace bounce
