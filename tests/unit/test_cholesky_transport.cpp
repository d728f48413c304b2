// The Cholesky solve of K = infinity (transport/symmetric_transport.h)
// against the LU of the same M (a second implementation, no areas given), on
// small balanced random matrices: A F symmetric, some patches of albedo 0.
// Also the fallbacks to the LU: F not balanced, S not positive definite.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "transport/inverse_transport.h"
#include "transport/spectral_radius.h"
#include "transport/transport.h"

namespace bounce {

namespace {

struct Balanced {
  std::size_t n = 0;
  std::vector<float> area, albedo, f;  // f row-major, A F symmetric to float rounding
};

// Symmetric non-negative G (some zeros), F = A^-1 G scaled so the largest
// row sums to `row_max`; albedo in [0.1, 0.95], every `dark_every`-th 0.
Balanced balanced(std::size_t n, unsigned seed, double row_max, std::size_t dark_every) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Balanced b;
  b.n = n;
  b.area.resize(n);
  b.albedo.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    b.area[p] = static_cast<float>(0.2 + 2.0 * u(rng));
    b.albedo[p] =
        dark_every && p % dark_every == 1 ? 0.0f : static_cast<float>(0.1 + 0.85 * u(rng));
  }
  std::vector<double> g(n * n, 0.0);
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t q = p; q < n; ++q) g[p * n + q] = g[q * n + p] = u(rng) < 0.15 ? 0.0 : u(rng);
  double worst = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    double row = 0.0;
    for (std::size_t q = 0; q < n; ++q) row += g[p * n + q] / b.area[p];
    worst = std::max(worst, row);
  }
  b.f.resize(n * n);
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t q = 0; q < n; ++q)
      b.f[p * n + q] = static_cast<float>(row_max / worst * g[p * n + q] / b.area[p]);
  return b;
}

std::vector<float> scaled_rows(const Balanced& b) {
  std::vector<float> m(b.n * b.n);
  for (std::size_t p = 0; p < b.n; ++p)
    for (std::size_t q = 0; q < b.n; ++q) m[p * b.n + q] = b.albedo[p] * b.f[p * b.n + q];
  return m;
}

InverseOptions with_areas(const Balanced& b) {
  InverseOptions o;
  o.area = b.area;
  o.albedo = b.albedo;
  return o;
}

// max |x - y| / max |y|: the normwise error the precision rule bounds.
double difference(const std::vector<float>& x, const std::vector<float>& y) {
  double d = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    d = std::max(d, std::abs(static_cast<double>(x[i]) - y[i]));
    scale = std::max(scale, std::abs(static_cast<double>(y[i])));
  }
  return d / scale;
}

}  // namespace

TEST(TransportCholesky, MatchesTheLuInBothPrecisions) {
  for (const std::size_t dark_every : {std::size_t{0}, std::size_t{7}}) {
    const Balanced b = balanced(90, 3, 0.95, dark_every);
    const std::vector<float> m = scaled_rows(b);
    for (const TransportPrecision precision :
         {TransportPrecision::Float32, TransportPrecision::Float64}) {
      InverseOptions lu_options, ch_options = with_areas(b);
      lu_options.force = ch_options.force = precision;
      const InverseTransport lu = solve_infinite_bounces(m, b.n, -1.0, lu_options);
      const InverseTransport ch = solve_infinite_bounces(m, b.n, -1.0, ch_options);
      ASSERT_EQ(lu.method, InverseMethod::LU);
      ASSERT_EQ(ch.method, InverseMethod::Cholesky) << ch.lu_reason;
      EXPECT_EQ(ch.precision, precision);
      EXPECT_LT(ch.asymmetry, 1e-6);
      // float64 is rounded to float32 T: a few float32 ulps apart.
      const double limit = precision == TransportPrecision::Float64 ? 1e-7 : 1e-5;
      EXPECT_LT(difference(ch.t, lu.t), limit)
          << precision_name(precision) << ", albedo 0 every " << dark_every;
      // Cholesky: n^3 / 3 + 2 n^3 flops (n - n_0 patches factorised).
      EXPECT_LT(ch.flops, lu.flops);
      // Patches of albedo 0 send nothing on: their rows of T are zero.
      for (std::size_t p = 0; p < b.n; ++p) {
        if (b.albedo[p] != 0.0f) continue;
        for (std::size_t q = 0; q < b.n; ++q) ASSERT_EQ(ch.t[p * b.n + q], 0.0f);
      }
    }
  }
}

TEST(TransportCholesky, PrecisionRuleAndInPlaceVariant) {
  const Balanced b = balanced(64, 5, 0.9, 5);
  std::vector<float> m = scaled_rows(b);
  const InverseTransport r = solve_infinite_bounces(m, b.n, -1.0, with_areas(b));
  EXPECT_EQ(r.method, InverseMethod::Cholesky);
  EXPECT_EQ(r.precision, TransportPrecision::Float32);  // rho < 0.9: well conditioned
  EXPECT_GT(r.condition, 1.0);
  EXPECT_NE(r.why.find("float32: condition estimate"), std::string::npos) << r.why;
  const InverseTransport in_place =
      solve_infinite_bounces_in_place(m.data(), b.n, -1.0, with_areas(b));
  EXPECT_TRUE(in_place.t.empty());
  EXPECT_EQ(m, r.t);  // bit for bit
}

TEST(TransportCholesky, FallsBackToTheLuWhenNotBalanced) {
  Balanced b = balanced(40, 9, 0.9, 0);
  b.f[3 * b.n + 17] *= 1.01f;  // one pair 1% off reciprocity
  const InverseTransport r = solve_infinite_bounces(scaled_rows(b), b.n, -1.0, with_areas(b));
  EXPECT_EQ(r.method, InverseMethod::LU);
  EXPECT_NE(r.lu_reason.find("not symmetric"), std::string::npos) << r.lu_reason;
}

TEST(TransportCholesky, FallsBackToTheLuWhenNotPositiveDefinite) {
  // Rows summing up to 20 at albedo 1: spectral radius > 1, S indefinite.
  Balanced b = balanced(40, 11, 20.0, 0);
  std::fill(b.albedo.begin(), b.albedo.end(), 1.0f);
  const InverseTransport r = solve_infinite_bounces(scaled_rows(b), b.n, -1.0, with_areas(b));
  EXPECT_EQ(r.method, InverseMethod::LU);
  EXPECT_NE(r.lu_reason.find("not positive definite"), std::string::npos) << r.lu_reason;
}

TEST(TransportCholesky, ComputeTransportUsesItWithAreas) {
  const Balanced b = balanced(50, 13, 0.9, 6);
  FormFactorMatrix f;
  f.n = b.n;
  f.values.assign(b.f.begin(), b.f.end());
  std::vector<glm::vec3> albedo(b.n);
  for (std::size_t p = 0; p < b.n; ++p) albedo[p] = glm::vec3(b.albedo[p]);
  TransportSettings s;
  s.bounces = TransportSettings::kInfiniteBounces;
  Diagnostics d;
  const TransportResult lu = compute_transport(f, albedo, s, nullptr, d);
  f.area = b.area;
  const TransportResult ch = compute_transport(f, albedo, s, nullptr, d);
  ASSERT_EQ(ch.channels.size(), 1u);
  EXPECT_EQ(ch.channels[0].method, "Cholesky float32");
  EXPECT_EQ(lu.channels[0].method, "LU float32");
  EXPECT_EQ(ch.backend, "none (no matrix product needed)");  // no GEMM timed
  EXPECT_GT(ch.flops, 0.0);
  EXPECT_LT(difference({ch.channels[0].t.begin(), ch.channels[0].t.end()},
                       {lu.channels[0].t.begin(), lu.channels[0].t.end()}),
            1e-5);
  // The radius read off T agrees with power iteration on M.
  const std::vector<float> m = scaled_rows(b);
  const SpectralRadius power = estimate_spectral_radius(m.data(), b.n);
  const ChannelTransport& c = ch.channels[0];
  EXPECT_NEAR(c.spectral_radius, power.estimate, 1e-4 * power.estimate);
  // Both are brackets of the same radius: they overlap.
  EXPECT_LE(c.spectral_radius_lower, power.upper * (1 + 1e-6));
  EXPECT_GE(c.spectral_radius_upper, power.lower * (1 - 1e-6));
}

}  // namespace bounce
