// Stiff and extreme cases of the real pipeline (the table is
// docs/stability.md). Each test states the outcome the math predicts and
// prints what it measured ("stability:" lines, copied into the doc).
//
// Bounds used throughout. F is non-negative with row sums s_p in
// [s_min, s_max], so for any h >= 1, s_min^h <= (F^h 1)_p <= s_max^h. With a
// uniform albedo rho, M = rho F and a uniform first hit b = 1:
//   sum_{h=1..K} (rho s_min)^h <= (T(K) 1)_p <= sum_{h=1..K} (rho s_max)^h,
// and for K = infinity rho s_min / (1 - rho s_min) <= (T 1)_p <= the same with
// s_max (only when rho s_max < 1). These are exact for the F the bake made, so
// the test holds T to them plus a rounding slack; how far they are from the
// ideal sum_h rho^h (a closed box has s = 1) is F's closure error, not the
// solver's, and is reported separately.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "bake/bake.h"
#include "base/error.h"
#include "test_scenes.h"

namespace bounce {
namespace {

BakeResult bake(const Scene& scene, int voxel, int bounces,
                std::optional<int> patches_per_voxel = std::nullopt) {
  BakeSettings s;
  s.voxel_resolution = voxel;
  s.patches_per_voxel = patches_per_voxel;
  s.codec = CodecChoice::Dense;
  s.transport.bounces = bounces;
  s.transport.backend = TransportSettings::Backend::OpenBLAS;
  s.pictures = false;
  Diagnostics d;
  Progress progress;
  return Baker(scene, s, d).run(progress);
}

struct RowSums {
  double min = 0.0, max = 0.0;
};

RowSums row_sums(const FormFactorMatrix& f) {
  RowSums r{1e300, -1e300};
  for (std::size_t p = 0; p < f.n; ++p) {
    double s = 0.0;
    for (std::size_t q = 0; q < f.n; ++q) s += f(p, q);
    r.min = std::min(r.min, s);
    r.max = std::max(r.max, s);
  }
  return r;
}

// sum_{h=1..K} x^h; K = -1 is infinity.
double series(double x, int k) {
  if (k < 0) return x < 1.0 ? x / (1.0 - x) : INFINITY;
  double sum = 0.0, term = 1.0;
  for (int h = 1; h <= k; ++h) sum += term *= x;
  return sum;
}

std::vector<double> times_ones(std::span<const float> t, std::size_t n) {
  std::vector<double> y(n, 0.0);
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t q = 0; q < n; ++q) y[p] += t[p * n + q];
  return y;
}

std::size_t non_finite(std::span<const float> v) {
  return static_cast<std::size_t>(
      std::count_if(v.begin(), v.end(), [](float x) { return !std::isfinite(x); }));
}

std::string k_name(int k) { return k < 0 ? "inf" : std::to_string(k); }

TEST(StabilityStiff, ClosedFurnaceAgainstTheTruncatedSeriesAndItsBound) {
  // Voxel 4: a few dozen patches, every row of F a closed box's (s = 1 ideally).
  for (const float rho_f : {0.5f, 0.9f, 0.99f, 0.999f}) {
    const double rho = rho_f;  // the float albedo the bake uses, exactly
    for (const int k : {1, 4, 16, TransportSettings::kInfiniteBounces}) {
      const Scene scene = test_scenes::furnace_box(glm::vec3(rho_f), glm::vec3(1.0f));
      // Balanced to the box's closure (1), every row sums to 1 within float
      // rounding, so even rho = 0.999 at K = infinity (rho(M) = 0.999)
      // solves; the raw quadrature's rows (up to 1.0064) made it diverge.
      const BakeResult r = bake(scene, 4, k);
      const std::size_t n = r.patches.size();
      ASSERT_GT(n, 1u);
      ASSERT_EQ(r.transport.channels.size(), 1u);  // grey
      const ChannelTransport& ct = r.transport.channels[0];
      EXPECT_EQ(non_finite(ct.t), 0u);
      const RowSums s = row_sums(r.form_factors);
      // The bake's own check agrees with ours.
      EXPECT_NEAR(r.checks.row_sum_max, s.max, 1e-6);
      // Perron-Frobenius: min row sum <= rho(M) <= max row sum.
      EXPECT_GE(ct.spectral_radius, rho * s.min * (1 - 1e-5));
      EXPECT_LE(ct.spectral_radius, rho * s.max * (1 + 1e-5));
      const double lo = series(rho * s.min, k), hi = series(rho * s.max, k);
      const double ideal = series(rho, k);
      // Rounding slack: float32 storage and products (~1e-6 relative per
      // product, K of them, or the LU's kappa * eps: at most 1e-5 by the
      // precision rule, inverse_transport.h), taken as 1e-4 relative.
      const double slack = 1e-4 * std::max(hi, lo);
      const std::vector<double> t1 = times_ones(ct.t, n);
      double worst_ideal = 0.0, t_min = 1e300, t_max = -1e300;
      for (std::size_t p = 0; p < n; ++p) {
        ASSERT_TRUE(std::isfinite(t1[p]));
        EXPECT_GE(t1[p], lo - slack) << "rho " << rho << " K " << k_name(k) << " patch " << p;
        if (std::isfinite(hi)) {
          EXPECT_LE(t1[p], hi + slack) << "rho " << rho << " K " << k_name(k) << " patch " << p;
        }
        worst_ideal = std::max(worst_ideal, std::abs(t1[p] - ideal) / ideal);
        // Closed rows: the ideal closed box's sum_h rho^h within 0.5%.
        EXPECT_NEAR(t1[p], ideal, 5e-3 * ideal)
            << "rho " << rho << " K " << k_name(k) << " patch " << p;
        t_min = std::min(t_min, t1[p]);
        t_max = std::max(t_max, t1[p]);
      }
      std::printf(
          "stability: furnace rho=%.3f K=%s n=%zu rows=[%.5f,%.5f] T1=[%.5g,%.5g] ideal=%.5g "
          "bound=[%.5g,%.5g] worst_rel_vs_ideal=%.3e method=%s precision=%s kappa=%.4g "
          "rho(M)=%.6f trunc=%.3g\n",
          rho, k_name(k).c_str(), n, s.min, s.max, t_min, t_max, ideal, lo, hi, worst_ideal,
          ct.method.c_str(), precision_name(ct.precision), ct.condition_number, ct.spectral_radius,
          ct.truncation_bound);
      if (k > 0) {
        EXPECT_TRUE(ct.method == "Horner" || ct.method == "doubling") << ct.method;
        EXPECT_EQ(ct.condition_number, 0.0);
      } else {
        // Balanced: A F symmetric, so the symmetric solve.
        EXPECT_EQ(ct.method, std::string("Cholesky ") + precision_name(ct.precision));
        EXPECT_GT(ct.condition_number, 1.0);
        // Precision rule: float32 only when kappa * FLT_EPSILON <= 1e-5.
        if (ct.precision == TransportPrecision::Float32) {
          EXPECT_LE(ct.condition_number * FLT_EPSILON, 1e-5);
        }
        // kappa_inf(I - M) >= 1 / (1 - rho(M)): rho = 0.99 and up must be float64.
        if (rho >= 0.99) {
          EXPECT_EQ(ct.precision, TransportPrecision::Float64);
        }
      }
    }
  }
}

Scene scaled(Scene s, float factor) {
  for (glm::vec3& p : s.positions) p *= factor;
  return s;
}

struct ScaleDifference {
  std::size_t n = 0, ref_n = 0;
  double df = 0.0, dt = 0.0, f_max = 0.0, t_max = 0.0;
};

ScaleDifference scale_difference(float factor) {
  const Scene base = test_scenes::furnace_box(glm::vec3(0.7f), glm::vec3(1.0f));
  const BakeResult ref = bake(base, 4, TransportSettings::kInfiniteBounces);
  const BakeResult r = bake(scaled(base, factor), 4, TransportSettings::kInfiniteBounces);
  ScaleDifference d;
  d.n = r.patches.size();
  d.ref_n = ref.patches.size();
  if (d.n != d.ref_n) return d;
  std::size_t worst_f = 0, differing = 0;
  d.f_max = ref.checks.value_max;
  for (std::size_t i = 0; i < ref.form_factors.values.size(); ++i) {
    const double e = std::abs(r.form_factors.values[i] - ref.form_factors.values[i]);
    if (e > 1e-6 * d.f_max) ++differing;
    if (e > d.df) {
      d.df = e;
      worst_f = i;
    }
  }
  const auto& t = r.transport.channels[0].t;
  const auto& t0 = ref.transport.channels[0].t;
  for (std::size_t i = 0; i < t0.size(); ++i) {
    d.dt = std::max(d.dt, static_cast<double>(std::abs(t[i] - t0[i])));
    d.t_max = std::max(d.t_max, static_cast<double>(t0[i]));
  }
  std::printf(
      "stability: scale %g n=%zu max|dF|=%.3e (F max %.3g) max|dT|=%.3e (T max %.3g); worst F "
      "entry (%zu,%zu) %.6g vs %.6g; %zu of %zu entries differ by > 1e-6 F max\n",
      factor, d.n, d.df, d.f_max, d.dt, d.t_max, worst_f / ref.form_factors.n,
      worst_f % ref.form_factors.n, r.form_factors.values[worst_f],
      ref.form_factors.values[worst_f], differing, ref.form_factors.values.size());
  return d;
}

TEST(StabilityExtreme, PowerOfTwoScaleGivesBitIdenticalFormFactorsAndTransport) {
  // Form factors are dimensionless and every length the pipeline uses is
  // relative to the scene (ray epsilon 1e-6 of the diagonal, voxel cells,
  // shadow rays ending at 1 - 1e-4 of the segment). Scaling by 2^+-13 is exact
  // in float32, so F and T must be bit for bit the same: they are.
  for (const float factor : {0x1p-13f, 0x1p13f}) {
    const ScaleDifference d = scale_difference(factor);
    ASSERT_EQ(d.n, d.ref_n) << "scale " << factor;
    EXPECT_EQ(d.df, 0.0) << "scale " << factor;
    EXPECT_EQ(d.dt, 0.0) << "scale " << factor;
  }
}

TEST(StabilityExtreme, DecimalScaleGivesTheSameFormFactorsToFloatTolerance) {
  // Scaling by 1e-4 or 1e4 (not powers of two) rounds the grid, the sampling
  // rays' origins and every derived coordinate differently: one float ulp,
  // 2^-24 ~ 6e-8 of the scene. No discrete choice flips (same voxels,
  // samples, triangles, patch members). A sampling ray that grazes a wall
  // turns its origin's ulp into a shift along the wall of 1/tan(angle) ulps
  // (measured: sample positions move by up to 2e-6 of the scene, ~34 ulps);
  // F, a smooth function of those positions, must then agree to that order:
  // 1e-5 of its largest entry (170 ulps) leaves a margin of ~5 for the sums.
  // Before the Voronoi cells and hit points were computed in double relative
  // to the sample (patches/samples.cpp), cancellation in absolute float
  // coordinates moved entries by up to 4e-4 of F max.
  for (const float factor : {1e-4f, 1e4f}) {
    const ScaleDifference d = scale_difference(factor);
    ASSERT_EQ(d.n, d.ref_n) << "scale " << factor;
    EXPECT_LE(d.df, 1e-5 * d.f_max) << "scale " << factor;
    EXPECT_LE(d.dt, 1e-5 * d.t_max) << "scale " << factor;
  }
}

BakeResult almost_touching() {
  Scene s;
  s.name = "almost-touching";
  test_scenes::add_quad(s, "bottom", {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  test_scenes::add_quad(s, "top", {0, 0, 1e-3f}, {0, 1, 1e-3f}, {1, 1, 1e-3f}, {1, 0, 1e-3f});
  return bake(s, 4, TransportSettings::kInfiniteBounces);
}

TEST(StabilityExtreme, AlmostTouchingParallelSquares) {
  // Two unit squares 1e-3 apart (analytic F between them 0.998). Expected:
  // no NaN/Inf, entries >= 0, rows <= 1.02 (the near-field quadrature error
  // the bake tolerates before warning, bake.cpp).
  const BakeResult r = almost_touching();
  const RowSums rs = row_sums(r.form_factors);
  std::printf(
      "stability: almost-touching n=%zu rows=[%.5f,%.5f] F max=%.5f clamped_to_one=%zu "
      "non_finite=%zu\n",
      r.patches.size(), rs.min, rs.max, r.checks.value_max, r.checks.clamped_to_one,
      r.checks.non_finite);
  EXPECT_EQ(r.checks.non_finite, 0u);
  EXPECT_EQ(non_finite(r.form_factors.values), 0u);
  for (const float v : r.form_factors.values) EXPECT_GE(v, 0.0f);
  EXPECT_LE(rs.max, 1.02);
  EXPECT_EQ(non_finite(r.transport.channels[0].t), 0u);
}

TEST(StabilityExtreme, AlmostTouchingFormFactorsAreAtMostOne) {
  // F_pq is the mean over P of the form factor from a point of P to Q, at
  // most 1 everywhere, so F_pq <= 1 exactly. The near-field quadrature (each
  // receiver piece refines the source its own way, and the integrand drops
  // from ~1 to ~0 within 1e-3 of a receiver's edge) estimated one entry at
  // 1.0008; the bake sets such entries to 1 (never further from the exact
  // value) and counts them in the manifest. They must stay rare: clamping
  // mends quadrature error, it is not how F is made.
  const BakeResult r = almost_touching();
  for (const float v : r.form_factors.values) EXPECT_LE(v, 1.0f);
  EXPECT_LE(r.checks.value_max, 1.0);
  EXPECT_LE(r.checks.clamped_to_one, r.form_factors.values.size() / 100);
}

TEST(StabilityExtreme, SingleTriangleFailsWithAClearError) {
  // One triangle sees nothing: every row of F is zero, so every patch is
  // pruned and the bake refuses with the reason.
  Scene s;
  s.name = "one-triangle";
  test_scenes::add_mesh(s, "tri", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
  try {
    bake(s, 4, TransportSettings::kInfiniteBounces);
    FAIL() << "a single triangle baked";
  } catch (const Error& e) {
    std::printf("stability: single triangle -> %s\n", e.what());
    EXPECT_NE(std::string(e.what()).find("no patch sees any other patch"), std::string::npos)
        << e.what();
  }
}

TEST(StabilityExtreme, BlackAlbedoGivesExactlyZeroTransport) {
  // M = 0 F = 0, so T = 0 for every K, exactly (0 * x = 0 in IEEE).
  for (const int k : {1, 4, TransportSettings::kInfiniteBounces}) {
    const BakeResult r = bake(test_scenes::furnace_box(glm::vec3(0.0f), glm::vec3(1.0f)), 4, k);
    const ChannelTransport& ct = r.transport.channels[0];
    std::size_t nonzero = 0;
    for (const float v : ct.t) nonzero += v != 0.0f;
    std::printf("stability: black K=%s n=%zu nonzero=%zu method=%s rho(M)=%g\n", k_name(k).c_str(),
                r.patches.size(), nonzero, ct.method.c_str(), ct.spectral_radius);
    EXPECT_EQ(nonzero, 0u) << "K " << k_name(k);
    EXPECT_EQ(non_finite(ct.t), 0u);
  }
}

TEST(StabilityExtreme, OneVoxel) {
  // voxel_resolution 1: the whole furnace box in one voxel, three patches
  // (one per normal cluster). Still a closed box: T 1 within the row-sum bound.
  const double rho = 0.5;
  const BakeResult r = bake(test_scenes::furnace_box(glm::vec3(0.5f), glm::vec3(1.0f)), 1,
                            TransportSettings::kInfiniteBounces);
  const std::size_t n = r.patches.size();
  const RowSums s = row_sums(r.form_factors);
  const std::vector<double> t1 = times_ones(r.transport.channels[0].t, n);
  std::printf("stability: one voxel n=%zu rows=[%.5f,%.5f] T1=[%.5g,%.5g] method=%s\n", n, s.min,
              s.max, *std::min_element(t1.begin(), t1.end()),
              *std::max_element(t1.begin(), t1.end()), r.transport.channels[0].method.c_str());
  EXPECT_GE(n, 1u);
  EXPECT_LE(n, 3u);
  for (std::size_t p = 0; p < n; ++p) {
    EXPECT_GE(t1[p], series(rho * s.min, -1) * (1 - 1e-4));
    EXPECT_LE(t1[p], series(rho * s.max, -1) * (1 + 1e-4));
  }
}

TEST(StabilityExtreme, OnePatch) {
  // N = 1. A closed box cannot get there: clustering never merges clusters
  // whose normals are more than 90 degrees apart, so voxel 1 with one patch
  // per voxel still gives three patches. A shallow V (two quads whose normals
  // are 60 degrees apart, facing each other) in one voxel can merge into one
  // patch; that patch's only form factor is its self term F00.
  const BakeResult box = bake(test_scenes::furnace_box(glm::vec3(0.5f), glm::vec3(1.0f)), 1,
                              TransportSettings::kInfiniteBounces, 1);
  std::printf("stability: furnace voxel 1, 1 patch/voxel -> n=%zu\n", box.patches.size());
  EXPECT_EQ(box.patches.size(), 3u);

  Scene v;
  v.name = "shallow-v";
  const float h = 0.5f * std::tan(30.0f * 3.14159265f / 180.0f);
  test_scenes::add_quad(v, "left", {0, 0, 0}, {1, 0, 0}, {1, 0.5f, -h}, {0, 0.5f, -h});
  test_scenes::add_quad(v, "right", {0, 0.5f, -h}, {1, 0.5f, -h}, {1, 1, 0}, {0, 1, 0});
  const double rho = 0.5;
  try {
    const BakeResult r = bake(v, 1, TransportSettings::kInfiniteBounces, 1);
    const double s = r.form_factors(0, 0);
    std::printf("stability: shallow V n=%zu F00=%.5f T00=%.6g expected=%.6g method=%s\n",
                r.patches.size(), s, r.transport.channels[0].t[0], series(rho * s, -1),
                r.transport.channels[0].method.c_str());
    ASSERT_EQ(r.patches.size(), 1u);
    EXPECT_NEAR(r.transport.channels[0].t[0], series(rho * s, -1), 1e-5);
  } catch (const Error& e) {
    std::printf("stability: shallow V -> %s\n", e.what());
    ADD_FAILURE() << e.what();
  }
}

}  // namespace
}  // namespace bounce
