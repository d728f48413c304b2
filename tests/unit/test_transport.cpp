// The multi-bounce transport stage (core/transport) against independent
// computations: repeated matrix-vector products, a Gauss-Jordan inverse in
// double, closed-form furnaces (white furnace: a closed
// enclosure with uniform albedo rho gives B = E / (1 - rho), i.e. the light
// after the first hit is T 1 = rho / (1 - rho) for unit first-hit light), and
// the real pipeline's furnace bake.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <span>
#include <string>

#include "bake/bake.h"
#include "base/error.h"
#include "scene/scene_loader.h"
#include "transport/bounce_series.h"
#include "transport/clblast_gemm.h"
#include "transport/spectral_radius.h"
#include "transport/transport.h"

namespace bounce {

namespace {

using Backend = TransportSettings::Backend;

// Random row-substochastic F: non-negative, each row summing to a random
// value in [0.5, 0.9), a few entries per row zero (occlusion).
FormFactorMatrix random_form_factors(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f), row_sum(0.5f, 0.9f);
  FormFactorMatrix f;
  f.n = n;
  f.values.resize(n * n);
  for (std::size_t p = 0; p < n; ++p) {
    double sum = 0.0;
    for (std::size_t q = 0; q < n; ++q) {
      const float v = u(rng) < 0.1f ? 0.0f : u(rng);
      f.values[p * n + q] = v;
      sum += v;
    }
    const float scale = row_sum(rng) / static_cast<float>(sum);
    for (std::size_t q = 0; q < n; ++q) f.values[p * n + q] *= scale;
  }
  return f;
}

std::vector<glm::vec3> random_albedo(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.05f, 0.95f);
  std::vector<glm::vec3> a(n);
  for (glm::vec3& x : a) x = {u(rng), u(rng), u(rng)};
  return a;
}

// The "uniform furnace": every patch sees every patch in proportion to its
// area, F_ij = A_j / A_total; rows sum to 1 (closed), F is reciprocal, and
// diag(rho) F = rho 1 a^T has the single non-zero eigenvalue rho.
FormFactorMatrix uniform_furnace(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.5, 2.0);
  std::vector<double> area(n);
  double total = 0.0;
  for (double& a : area) total += a = u(rng);
  FormFactorMatrix f;
  f.n = n;
  f.values.resize(n * n);
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t q = 0; q < n; ++q) f.values[p * n + q] = static_cast<float>(area[q] / total);
  return f;
}

std::vector<double> row_scaled(const FormFactorMatrix& f, const std::vector<glm::vec3>& albedo,
                               int c) {
  std::vector<double> m(f.n * f.n);
  for (std::size_t p = 0; p < f.n; ++p)
    for (std::size_t q = 0; q < f.n; ++q)
      m[p * f.n + q] = static_cast<double>(albedo[p][c]) * f.values[p * f.n + q];
  return m;
}

std::vector<double> matvec(const std::vector<double>& m, const std::vector<double>& x) {
  const std::size_t n = x.size();
  std::vector<double> y(n, 0.0);
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t q = 0; q < n; ++q) y[p] += m[p * n + q] * x[q];
  return y;
}

std::vector<double> matvec(std::span<const float> t, const std::vector<double>& x) {
  return matvec(std::vector<double>(t.begin(), t.end()), x);
}

// sum_(h=1..K) M^h b by K explicit products in double (K < 0: until the terms
// fall below 1e-14 of the sum).
std::vector<double> explicit_bounces(const std::vector<double>& m, std::vector<double> b,
                                     int bounces) {
  std::vector<double> sum(b.size(), 0.0);
  for (int h = 1; bounces < 0 || h <= bounces; ++h) {
    b = matvec(m, b);
    double term = 0.0, total = 0.0;
    for (std::size_t i = 0; i < b.size(); ++i) {
      sum[i] += b[i];
      term = std::max(term, std::abs(b[i]));
      total = std::max(total, std::abs(sum[i]));
    }
    if (bounces < 0 && term <= 1e-14 * total) break;
    if (h > 100000) break;
  }
  return sum;
}

double max_abs(const std::vector<double>& x) {
  double m = 0.0;
  for (double v : x) m = std::max(m, std::abs(v));
  return m;
}

double max_rel_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d / max_abs(b);
}

std::vector<double> random_vector(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> b(n);
  for (double& x : b) x = u(rng);
  return b;
}

bool has_opencl_device() {
  try {
    ClblastGemm probe;
    return true;
  } catch (const Error&) {
    return false;
  }
}

TransportResult transport(const FormFactorMatrix& f, const std::vector<glm::vec3>& albedo,
                          int bounces, Backend backend = Backend::OpenBLAS) {
  TransportSettings s;
  s.bounces = bounces;
  s.backend = backend;
  Diagnostics d;
  return compute_transport(f, albedo, s, nullptr, d);
}

bool has_decision(const TransportResult& r, const std::string& text) {
  return std::any_of(r.decisions.begin(), r.decisions.end(), [&](const TransportDecision& d) {
    return d.what.find(text) != std::string::npos || d.why.find(text) != std::string::npos;
  });
}

// T b against K explicit products, every channel. Tolerance 1e-5 K relative:
// each float32 product of non-negative matrices errs by about sqrt(N) u ~ 1e-6
// relative for N = 200 (u = 6e-8, random rounding), and the K products of
// either scheme add up.
void expect_matches_explicit_products(Backend backend) {
  const std::size_t n = 200;
  const FormFactorMatrix f = random_form_factors(n, 1);
  const std::vector<glm::vec3> albedo = random_albedo(n, 2);
  const std::vector<double> b = random_vector(n, 3);
  for (int bounces : {1, 2, 3, 5, 6, 13}) {
    const TransportResult r = transport(f, albedo, bounces, backend);
    ASSERT_EQ(r.channels.size(), 3u);
    if (bounces > 1 && backend == Backend::CLBlast) {
      EXPECT_NE(r.backend.find("CLBlast"), std::string::npos) << r.backend;
      EXPECT_EQ(r.backend.find("failed"), std::string::npos) << r.backend;
    }
    for (int c = 0; c < 3; ++c) {
      const ChannelTransport& ct = r.channel(c);
      EXPECT_EQ(ct.bounces, bounces);
      const std::vector<double> expected = explicit_bounces(row_scaled(f, albedo, c), b, bounces);
      const double err = max_rel_diff(matvec(ct.t, b), expected);
      EXPECT_LT(err, 1e-5 * bounces) << "K = " << bounces << ", channel " << c << ", " << ct.method;
    }
  }
}

}  // namespace

TEST(TransportSeries, PlanPicksTheCheaperScheme) {
  EXPECT_EQ(plan_series(1).gemms, 0);
  EXPECT_EQ(plan_series(2).gemms, 1);
  EXPECT_EQ(plan_series(3).scheme, SeriesScheme::Horner);  // tie: 2 and 2
  EXPECT_EQ(plan_series(3).gemms, 2);
  EXPECT_EQ(plan_series(4).scheme, SeriesScheme::Doubling);
  EXPECT_EQ(plan_series(4).gemms, 2);
  EXPECT_EQ(plan_series(8).gemms, 4);
  EXPECT_EQ(plan_series(64).gemms, 10);
  EXPECT_EQ(plan_series(64).horner_gemms, 63);
  for (int k = 1; k <= 64; ++k) EXPECT_LE(plan_series(k).gemms, k - 1) << k;
}

TEST(TransportSeries, MatchesExplicitProductsOpenBlas) {
  expect_matches_explicit_products(Backend::OpenBLAS);
}

TEST(TransportSeries, MatchesExplicitProductsClblast) {
  if (!has_opencl_device()) GTEST_SKIP() << "no OpenCL device";
  expect_matches_explicit_products(Backend::CLBlast);
}

TEST(TransportSeries, BackendsAgree) {
  if (!has_opencl_device()) GTEST_SKIP() << "no OpenCL device";
  const std::size_t n = 160;
  const FormFactorMatrix f = random_form_factors(n, 4);
  const std::vector<glm::vec3> albedo = random_albedo(n, 5);
  const TransportResult a = transport(f, albedo, 9, Backend::OpenBLAS);
  const TransportResult b = transport(f, albedo, 9, Backend::CLBlast);
  for (int c = 0; c < 3; ++c) {
    const std::vector<double> ta(a.channel(c).t.begin(), a.channel(c).t.end());
    const std::vector<double> tb(b.channel(c).t.begin(), b.channel(c).t.end());
    EXPECT_LT(max_rel_diff(tb, ta), 1e-5) << "channel " << c;
  }
}

TEST(TransportSeries, AutoBackendProbesBothAndRecordsTimings) {
  const std::size_t n = 128;
  const FormFactorMatrix f = random_form_factors(n, 6);
  TransportSettings s;
  s.bounces = 4;
  s.backend = Backend::Auto;
  s.auto_probe_min_seconds = 0.0;  // probe even this small problem
  Diagnostics d;
  const TransportResult r = compute_transport(f, random_albedo(n, 7), s, nullptr, d);
  EXPECT_GT(r.probe_openblas_seconds, 0.0);
  if (has_opencl_device()) {
    EXPECT_GT(r.probe_clblast_seconds, 0.0);
    EXPECT_EQ(r.probe_n, n);
    EXPECT_TRUE(has_decision(r, "OpenBLAS")) << r.backend;
    EXPECT_TRUE(has_decision(r, "CLBlast")) << r.backend;
  }
  if (r.probe_clblast_seconds > 0.0 && r.probe_clblast_seconds < r.probe_openblas_seconds)
    EXPECT_NE(r.backend.find("CLBlast"), std::string::npos) << r.backend;
  else
    EXPECT_EQ(r.backend, "OpenBLAS");
  for (const TransportDecision& x : r.decisions)
    std::printf("  %s -- %s\n", x.what.c_str(), x.why.c_str());

  // Small problems do not pay for the probe.
  s.auto_probe_min_seconds = 1.0;
  const TransportResult small = compute_transport(f, random_albedo(n, 7), s, nullptr, d);
  EXPECT_EQ(small.backend, "OpenBLAS");
  EXPECT_TRUE(has_decision(small, "not probed"));
}

TEST(TransportInfinite, MatchesSeriesAndGaussJordan) {
  const std::size_t n = 120;
  const FormFactorMatrix f = random_form_factors(n, 8);
  const std::vector<glm::vec3> albedo = random_albedo(n, 9);
  const TransportResult r = transport(f, albedo, TransportSettings::kInfiniteBounces);
  ASSERT_EQ(r.channels.size(), 3u);
  const std::vector<double> b = random_vector(n, 10);
  for (int c = 0; c < 3; ++c) {
    const ChannelTransport& ct = r.channel(c);
    EXPECT_EQ(ct.bounces, TransportSettings::kInfiniteBounces);
    EXPECT_GT(ct.condition_number, 1.0);
    const std::vector<double> m = row_scaled(f, albedo, c);
    // The series summed until it stops changing.
    EXPECT_LT(max_rel_diff(matvec(ct.t, b), explicit_bounces(m, b, -1)), 1e-4) << c;
    // (I - M)^-1 - I by Gauss-Jordan with partial pivoting, in double.
    std::vector<double> a(n * n), inv(n * n, 0.0);
    for (std::size_t i = 0; i < n * n; ++i) a[i] = -m[i];
    for (std::size_t i = 0; i < n; ++i) a[i * n + i] += 1.0, inv[i * n + i] = 1.0;
    for (std::size_t col = 0; col < n; ++col) {
      std::size_t pivot = col;
      for (std::size_t row = col + 1; row < n; ++row)
        if (std::abs(a[row * n + col]) > std::abs(a[pivot * n + col])) pivot = row;
      for (std::size_t j = 0; j < n; ++j) {
        std::swap(a[col * n + j], a[pivot * n + j]);
        std::swap(inv[col * n + j], inv[pivot * n + j]);
      }
      const double d = a[col * n + col];
      for (std::size_t j = 0; j < n; ++j) a[col * n + j] /= d, inv[col * n + j] /= d;
      for (std::size_t row = 0; row < n; ++row) {
        if (row == col) continue;
        const double x = a[row * n + col];
        for (std::size_t j = 0; j < n; ++j) {
          a[row * n + j] -= x * a[col * n + j];
          inv[row * n + j] -= x * inv[col * n + j];
        }
      }
    }
    for (std::size_t i = 0; i < n; ++i) inv[i * n + i] -= 1.0;
    const std::vector<double> t(ct.t.begin(), ct.t.end());
    EXPECT_LT(max_rel_diff(t, inv), 1e-4) << "channel " << c << ", " << ct.method;
  }
}

TEST(TransportInfinite, UniformFurnaceGivesRhoOverOneMinusRho) {
  const std::size_t n = 150;
  const FormFactorMatrix f = uniform_furnace(n, 11);
  // Condition of I - rho 1 a^T in the inf-norm: (1 + rho) / (1 - rho), so
  // kappa * FLT_EPSILON is 3.6e-7 (0.5), 2.3e-6 (0.9), 2.4e-5 (0.99): float64
  // from 0.99 on (limit 1e-5, inverse_transport.h).
  struct Case {
    float rho;
    TransportPrecision precision;
  };
  for (const Case& k :
       {Case{0.5f, TransportPrecision::Float32}, Case{0.9f, TransportPrecision::Float32},
        Case{0.99f, TransportPrecision::Float64}}) {
    const std::vector<glm::vec3> albedo(n, glm::vec3(k.rho));
    const TransportResult r = transport(f, albedo, TransportSettings::kInfiniteBounces);
    ASSERT_EQ(r.channels.size(), 1u);
    const ChannelTransport& ct = r.channels[0];
    EXPECT_EQ(ct.precision, k.precision) << "rho " << k.rho;
    EXPECT_NEAR(ct.spectral_radius, k.rho, 1e-5 * k.rho);
    EXPECT_NEAR(ct.condition_number, (1.0 + k.rho) / (1.0 - k.rho),
                0.1 * (1.0 + k.rho) / (1.0 - k.rho));
    const double expected = k.rho / (1.0 - k.rho);
    const std::vector<double> t1 = matvec(ct.t, std::vector<double>(n, 1.0));
    for (std::size_t p = 0; p < n; ++p)
      ASSERT_NEAR(t1[p], expected, 0.01 * expected) << "rho " << k.rho << ", patch " << p;
  }
}

TEST(TransportInfinite, RealFurnaceBake) {
  Diagnostics d;
  const Scene scene = SceneLoader(d).load(std::string(BOUNCE_RESOURCE_DIR) + "/scenes/furnace");
  BakeSettings bs;
  bs.voxel_resolution = 6;
  Progress progress;
  const BakeResult bake = Baker(scene, bs, d).run(progress);
  const std::size_t n = bake.patches.size();
  std::vector<glm::vec3> albedo;
  for (const Patch& p : bake.patches.patches) albedo.push_back(p.albedo);
  const TransportResult r =
      transport(bake.form_factors, albedo, TransportSettings::kInfiniteBounces);
  ASSERT_TRUE(r.grey);
  const ChannelTransport& ct = r.channels[0];
  // With row sums s_i and albedo rho, (T 1)_i = rho s_i (1 + (T 1) averaged
  // by row i), and T 1 lies between rho s_min / (1 - rho s_min) and the same
  // with s_max: an honest bound for each row from the actual row sums.
  std::vector<double> s(n, 0.0);
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t q = 0; q < n; ++q) s[p] += bake.form_factors(p, q);
  const double rho = albedo[0].r;
  const double s_min = *std::min_element(s.begin(), s.end());
  const double s_max = *std::max_element(s.begin(), s.end());
  const double lo = rho * s_min / (1.0 - rho * s_min), hi = rho * s_max / (1.0 - rho * s_max);
  const std::vector<double> t1 = matvec(ct.t, std::vector<double>(n, 1.0));
  double worst = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    const double tol = 1e-4 * hi;  // float32 solve
    EXPECT_GE(t1[p], rho * s[p] * (1.0 + lo) - tol) << "patch " << p;
    EXPECT_LE(t1[p], rho * s[p] * (1.0 + hi) + tol) << "patch " << p;
    worst = std::max(worst, std::abs(t1[p] - rho / (1.0 - rho)));
  }
  std::printf("furnace bake: %zu patches, row sums %.4f..%.4f, T(inf) 1 within %.4f of %.4f\n", n,
              s_min, s_max, worst, rho / (1.0 - rho));
  EXPECT_NEAR(rho, 0.5, 1e-6);
  // Against rho / (1 - rho) = 1 itself: 1%, plus what the row sums can move
  // the exact answer (the bounds above).
  EXPECT_LT(worst, 0.01 + std::max(hi - 1.0, 1.0 - lo));
}

TEST(TransportAuto, StopsWhereTheNextBounceAddsLessThanTheTolerance) {
  // Uniform furnace, rho = 0.5: e_h = n rho^h, so bounce K + 1 adds
  // rho^K (1 - rho) / (1 - rho^K) of the light so far: 1.96e-3 at K = 8,
  // 9.8e-4 at K = 9. The series to K = 9 takes 5 products, the exact LU
  // about 1.5: auto computes K = infinity and says where the series stopped.
  const std::size_t n = 64;
  const FormFactorMatrix f = uniform_furnace(n, 12);
  const std::vector<glm::vec3> half(n, glm::vec3(0.5f));
  const TransportResult r = transport(f, half, TransportSettings::kAutoBounces);
  ASSERT_EQ(r.channels.size(), 1u);
  EXPECT_EQ(r.channels[0].auto_bounces, 9);
  EXPECT_EQ(r.channels[0].bounces, TransportSettings::kInfiniteBounces);
  EXPECT_TRUE(has_decision(r, "converges at K = 9 (auto)"));
  EXPECT_TRUE(has_decision(r, "K = infinity (auto)"));

  // The truncation bound is exact here: the Perron vector is 1 and the tail
  // for b = 1 is sum_(h>9) rho^h = rho^10 / (1 - rho).
  const TransportResult k9 = transport(f, half, 9);
  EXPECT_NEAR(k9.channels[0].truncation_bound, std::pow(0.5, 10) / 0.5, 1e-6);
  const std::vector<double> one(n, 1.0);
  const std::vector<double> all = matvec(r.channels[0].t, one);
  const std::vector<double> head = matvec(k9.channels[0].t, one);
  EXPECT_NEAR(all[0] - head[0], std::pow(0.5, 10) / 0.5, 1e-5);

  // Albedo 0.02: K = 2 (3.9e-4 < 1e-3), one product, cheaper than the LU:
  // the truncated series is kept and the later bounces reported left out.
  Diagnostics d;
  TransportSettings s;
  const TransportResult dark =
      compute_transport(f, std::vector<glm::vec3>(n, glm::vec3(0.02f)), s, nullptr, d);
  EXPECT_EQ(dark.channels[0].bounces, 2);
  EXPECT_EQ(dark.channels[0].auto_bounces, 2);
  EXPECT_FALSE(d.left_outs().empty());

  // On a random matrix: the K found is the first with e_(K+1) < tol sum e_h.
  const std::size_t m = 100;
  const FormFactorMatrix g = random_form_factors(m, 13);
  const std::vector<glm::vec3> albedo = random_albedo(m, 14);
  const TransportResult a = transport(g, albedo, TransportSettings::kAutoBounces);
  for (int c = 0; c < 3; ++c) {
    const int k = a.channel(c).auto_bounces;
    ASSERT_GE(k, 1) << "channel " << c;
    const std::vector<double> mc = row_scaled(g, albedo, c);
    std::vector<double> v(m, 1.0), e;
    for (int h = 0; h <= k; ++h) {
      v = matvec(mc, v);
      double sum = 0.0;
      for (double x : v) sum += x;
      e.push_back(sum);
    }
    double so_far = 0.0;
    for (int h = 0; h < k; ++h) so_far += e[h];
    EXPECT_LT(e[k], 1e-3 * so_far) << "channel " << c << " K " << k;
    if (k > 1) {
      EXPECT_GE(e[k - 1], 1e-3 * (so_far - e[k - 1])) << "channel " << c << " K " << k;
    }
  }
}

TEST(TransportAuto, FallsBackToInfinityWhenTheSeriesIsSlow) {
  const std::size_t n = 64;
  const FormFactorMatrix f = uniform_furnace(n, 15);
  const TransportResult r = transport(f, std::vector<glm::vec3>(n, glm::vec3(0.99f)), 0);
  EXPECT_EQ(r.channels[0].bounces, TransportSettings::kInfiniteBounces);
  EXPECT_TRUE(has_decision(r, "K = infinity (auto)"));
}

TEST(TransportSpectralRadius, KnownSpectra) {
  // Uniform furnace: diag(rho) F = rho 1 a^T, spectrum {rho, 0, ...}.
  const std::size_t n = 80;
  const FormFactorMatrix f = uniform_furnace(n, 16);
  std::vector<float> m(f.values.begin(), f.values.end());
  for (float& x : m) x *= 0.7f;
  const SpectralRadius r = estimate_spectral_radius(m.data(), n);
  EXPECT_NEAR(r.estimate, 0.7, 1e-5);
  EXPECT_LE(r.lower, 0.7 + 1e-5);
  EXPECT_GE(r.upper, 0.7 - 1e-5);
  // Reducible: two furnaces that do not see each other, rho 0.3 and 0.8, plus
  // a patch of albedo 0; the spectral radius is 0.8 and the lower bound
  // cannot leave 0.
  const std::size_t h = 40, size = 2 * h + 1;
  std::vector<float> b(size * size, 0.0f);
  for (std::size_t p = 0; p < h; ++p)
    for (std::size_t q = 0; q < h; ++q) {
      b[p * size + q] = 0.3f / static_cast<float>(h);
      b[(h + p) * size + h + q] = 0.8f / static_cast<float>(h);
    }
  const SpectralRadius rb = estimate_spectral_radius(b.data(), size);
  EXPECT_NEAR(rb.estimate, 0.8, 1e-4);
  EXPECT_GE(rb.upper, 0.8 - 1e-6);
  EXPECT_TRUE(rb.converged);
}

TEST(TransportChannels, GreySceneGivesOneChannelColouredThree) {
  const std::size_t n = 50;
  const FormFactorMatrix f = random_form_factors(n, 17);
  std::vector<glm::vec3> grey(n);
  for (std::size_t p = 0; p < n; ++p)
    grey[p] = glm::vec3(0.1f + 0.8f * static_cast<float>(p) / static_cast<float>(n));
  TransportSettings s;
  s.bounces = 3;
  Diagnostics d;
  const TransportResult g = compute_transport(f, grey, s, nullptr, d);
  EXPECT_TRUE(g.grey);
  ASSERT_EQ(g.channels.size(), 1u);
  EXPECT_EQ(g.channels[0].rgb, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(&g.channel(0), &g.channel(2));
  EXPECT_TRUE(has_decision(g, "grey scene: one channel stands for R, G and B"));
  EXPECT_FALSE(d.left_outs().empty());

  const TransportResult c = compute_transport(f, random_albedo(n, 18), s, nullptr, d);
  EXPECT_FALSE(c.grey);
  EXPECT_EQ(c.channels.size(), 3u);

  // R = G != B: two matrices, R and G share one.
  std::vector<glm::vec3> two = grey;
  for (glm::vec3& a : two) a.b *= 0.5f;
  const TransportResult t = compute_transport(f, two, s, nullptr, d);
  ASSERT_EQ(t.channels.size(), 2u);
  EXPECT_EQ(&t.channel(0), &t.channel(1));
  EXPECT_NE(&t.channel(0), &t.channel(2));
}

TEST(TransportErrors, RejectsNonFiniteAndDivergentInput) {
  const std::size_t n = 20;
  FormFactorMatrix f = random_form_factors(n, 19);
  const std::vector<glm::vec3> albedo = random_albedo(n, 20);
  f.values[3 * n + 7] = std::nanf("");
  try {
    transport(f, albedo, 3);
    FAIL() << "NaN accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("NaN"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("F[3][7]"), std::string::npos) << e.what();
  }
  f = random_form_factors(n, 19);
  std::vector<glm::vec3> bad = albedo;
  bad[5].g = std::numeric_limits<float>::infinity();
  EXPECT_THROW(transport(f, bad, 3), Error);

  // Rows summing to 1.2 with albedo 0.95: spectral radius 1.14.
  FormFactorMatrix over = uniform_furnace(n, 21);
  for (float& x : over.values) x *= 1.2f;
  const std::vector<glm::vec3> bright(n, glm::vec3(0.95f));
  try {
    transport(over, bright, TransportSettings::kInfiniteBounces);
    FAIL() << "divergent K = infinity accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("energy is not conserved"), std::string::npos) << e.what();
  }
  EXPECT_THROW(transport(over, bright, TransportSettings::kAutoBounces), Error);
  // An explicit K is still finite: computed, with a warning.
  TransportSettings s;
  s.bounces = 3;
  Diagnostics d;
  const TransportResult r = compute_transport(over, bright, s, nullptr, d);
  EXPECT_TRUE(std::isinf(r.channels[0].truncation_bound));
  EXPECT_FALSE(d.warnings().empty());

  s.bounces = 65;
  EXPECT_THROW(compute_transport(over, bright, s, nullptr, d), Error);
}

TEST(TransportProgress, ReportsAndCancels) {
  const std::size_t n = 64;
  const FormFactorMatrix f = random_form_factors(n, 22);
  TransportSettings s;
  s.bounces = 16;
  s.backend = Backend::OpenBLAS;
  Diagnostics d;
  double last = -1.0;
  bool monotone = true;
  Progress progress([&](const std::string& stage, double fraction) {
    EXPECT_EQ(stage, "transport");
    monotone = monotone && fraction >= last;
    last = fraction;
    return true;
  });
  compute_transport(f, random_albedo(n, 23), s, &progress, d);
  EXPECT_TRUE(monotone);
  EXPECT_DOUBLE_EQ(last, 1.0);

  Progress stop([](const std::string&, double fraction) { return fraction < 0.3; });
  EXPECT_THROW(compute_transport(f, random_albedo(n, 23), s, &stop, d), Cancelled);
}

}  // namespace bounce
