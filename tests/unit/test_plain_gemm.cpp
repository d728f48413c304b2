// The plain triple-loop GEMM (the naive baseline of `bounce bench transport`)
// against OpenBLAS. Two float32 products of the same matrices differ only by
// rounding: each entry of either is within gamma_n (|A||B|)_ij of the exact
// product, gamma_n ~ n u with u = eps / 2 (Higham, Accuracy and Stability of
// Numerical Algorithms, 2nd ed., section 3.5), so they differ by at most
// n eps (|A||B|)_ij (plus |beta C| eps for the beta term). n = 67 is odd and
// not a multiple of any SIMD width, so remainders of vectorised loops run.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "transport/openblas_gemm.h"
#include "transport/plain_gemm.h"

namespace bounce {

namespace {

constexpr std::size_t kN = 67;

std::vector<float> random_matrix(std::size_t n, unsigned seed) {
  // Signed entries: cancellation makes |AB| much smaller than |A||B| in
  // places, which is where a wrong tolerance would show.
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> m(n * n);
  for (float& x : m) x = u(rng);
  return m;
}

// Checks plain against OpenBLAS for one beta; C starts as `c0` in both.
void expect_same_product(float beta) {
  const std::size_t n = kN;
  const std::vector<float> a = random_matrix(n, 1), b = random_matrix(n, 2),
                           c0 = random_matrix(n, 3);
  std::vector<float> plain_c = c0, blas_c = c0;
  PlainGemm plain;
  OpenBlasGemm openblas;
  plain.multiply(n, a.data(), b.data(), beta, plain_c.data());
  openblas.multiply(n, a.data(), b.data(), beta, blas_c.data());

  const double eps = std::numeric_limits<float>::epsilon();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      double magnitude = std::abs(static_cast<double>(beta) * c0[i * n + j]);
      for (std::size_t k = 0; k < n; ++k)
        magnitude += std::abs(static_cast<double>(a[i * n + k]) * b[k * n + j]);
      const double tolerance = static_cast<double>(n + 1) * eps * magnitude;
      ASSERT_NEAR(plain_c[i * n + j], blas_c[i * n + j], tolerance)
          << "entry (" << i << ", " << j << "), beta " << beta;
    }
}

}  // namespace

TEST(PlainGemm, MatchesOpenBlasWithBetaZero) { expect_same_product(0.0f); }

TEST(PlainGemm, MatchesOpenBlasWithBetaOne) { expect_same_product(1.0f); }

TEST(PlainGemm, MatchesOpenBlasWithBetaHalf) { expect_same_product(0.5f); }

TEST(PlainGemm, BetaZeroOverwritesNaN) {
  // BLAS semantics: with beta = 0, C is output only, whatever it held.
  const std::size_t n = kN;
  const std::vector<float> a = random_matrix(n, 4), b = random_matrix(n, 5);
  std::vector<float> c(n * n, std::numeric_limits<float>::quiet_NaN());
  PlainGemm plain;
  plain.multiply(n, a.data(), b.data(), 0.0f, c.data());
  for (float x : c) ASSERT_TRUE(std::isfinite(x));
}

}  // namespace bounce
