// Temporal radiosity (dynamic/temporal_radiosity.h, alias_table.h): the alias
// tables represent each row's distribution exactly and sample it (chi-square),
// the per-frame estimate is unbiased, the blend converges to the full product
// T b, and the OpenCL kernel reproduces the C++ path on the same stream; the
// bench's picture measures agree with its patch errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "base/error.h"
#include "base/random.h"
#include "compute/opencl_context.h"
#include "dynamic/alias_table.h"
#include "dynamic/counter_hash.h"
#include "dynamic/temporal_radiosity.h"
#include "dynamic/temporal_radiosity_cl.h"
#include "dynamic_bench.h"

namespace bounce {
namespace {

std::vector<float> random_matrix(std::size_t n, std::uint64_t seed, float zero_share = 0.3f) {
  std::vector<float> t(n * n);
  Rng rng(seed, 1);
  for (float& x : t) {
    const float u = rng.uniform();
    x = u < zero_share ? 0.0f : u * u * 0.1f;
  }
  return t;
}

std::vector<glm::vec3> random_light(std::size_t n, std::uint64_t seed) {
  std::vector<glm::vec3> b(n);
  Rng rng(seed, 2);
  for (auto& v : b) v = glm::vec3(rng.uniform(), rng.uniform(), rng.uniform());
  return b;
}

std::vector<glm::vec3> full_product(const std::vector<const float*>& t, std::size_t n,
                                    const std::array<int, 3>& map,
                                    const std::vector<glm::vec3>& b) {
  std::vector<glm::vec3> y(n, glm::vec3(0.0f));
  for (std::size_t p = 0; p < n; ++p)
    for (int k = 0; k < 3; ++k) {
      double sum = 0.0;
      const float* row = t[static_cast<std::size_t>(map[static_cast<std::size_t>(k)])] + p * n;
      for (std::size_t q = 0; q < n; ++q) sum += static_cast<double>(row[q]) * b[q][k];
      y[p][k] = static_cast<float>(sum);
    }
  return y;
}

// Upper chi-square quantile by Wilson-Hilferty, z the normal quantile.
double chi_square_quantile(double df, double z) {
  const double a = 2.0 / (9.0 * df);
  return df * std::pow(1.0 - a + z * std::sqrt(a), 3.0);
}

TEST(DynamicAliasTable, RepresentsEachRowExactly) {
  // The probability a table gives outcome j, (probability[j] + sum over i
  // aliased to j of (1 - probability[i])) / n, must be w_j / sum w.
  const std::size_t n = 37;
  std::vector<float> rows = random_matrix(n, 5);
  // Edge cases: a single non-zero, all equal, all zero, a negative rounding.
  std::fill(rows.begin(), rows.begin() + n, 0.0f);
  rows[4] = 2.0f;
  std::fill(rows.begin() + n, rows.begin() + 2 * n, 0.25f);
  std::fill(rows.begin() + 2 * n, rows.begin() + 3 * n, 0.0f);
  rows[3 * n + 5] = -1e-9f;
  const AliasTables t = build_alias_tables(rows.data(), n, n);
  for (std::size_t r = 0; r < n; ++r) {
    const float* w = rows.data() + r * n;
    double sum = 0.0;
    for (std::size_t j = 0; j < n; ++j) sum += std::max(w[j], 0.0f);
    EXPECT_NEAR(t.row_sum[r], sum, 1e-6 * sum);
    if (sum == 0.0) continue;
    std::vector<double> p(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const float pr = t.entries[r * n + i].probability;
      ASSERT_GE(pr, 0.0f);
      ASSERT_LE(pr, 1.0f);
      p[i] += pr;
      p[t.entries[r * n + i].alias] += 1.0 - pr;
    }
    for (std::size_t j = 0; j < n; ++j)
      EXPECT_NEAR(p[j] / static_cast<double>(n), std::max(w[j], 0.0f) / sum, 1e-6)
          << "row " << r << " column " << j;
  }
}

TEST(DynamicAliasTable, SamplesTheRowDistributionChiSquare) {
  const std::size_t n = 24, draws = 200000;
  const std::vector<float> rows = random_matrix(n, 9);
  const AliasTables t = build_alias_tables(rows.data(), n, n);
  for (std::size_t r = 0; r < 4; ++r) {
    std::vector<double> count(n, 0.0);
    const auto row = static_cast<std::uint32_t>(r);
    for (std::uint32_t s = 0; s < draws; ++s) {
      const std::uint32_t i =
          hash_to_index(sample_hash(3, 0, row, s, 0), static_cast<std::uint32_t>(n));
      const float u = hash_to_unit(sample_hash(3, 0, row, s, 1));
      count[alias_sample(t.entries.data() + r * n, i, u)] += 1.0;
    }
    double chi2 = 0.0;
    int df = -1;
    for (std::size_t j = 0; j < n; ++j) {
      const double expected = draws * rows[r * n + j] / t.row_sum[r];
      if (expected == 0.0) {
        EXPECT_EQ(count[j], 0.0) << "zero-weight column " << j << " was drawn";
        continue;
      }
      chi2 += (count[j] - expected) * (count[j] - expected) / expected;
      ++df;
    }
    // p = 0.001 (z = 3.09): a correct sampler fails one row in a thousand.
    EXPECT_LT(chi2, chi_square_quantile(df, 3.09)) << "row " << r << ", df " << df;
  }
}

struct TemporalCase {
  std::size_t n = 32;
  std::vector<std::vector<float>> t;
  std::vector<const float*> ptrs;
  std::array<int, 3> map{0, 1, 2};
  std::vector<glm::vec3> b, reference;
};

TemporalCase make_case(std::size_t n, int channels, std::array<int, 3> map) {
  TemporalCase c;
  c.n = n;
  c.map = map;
  for (int ch = 0; ch < channels; ++ch)
    c.t.push_back(random_matrix(n, 20 + static_cast<std::uint64_t>(ch)));
  for (const auto& m : c.t) c.ptrs.push_back(m.data());
  c.b = random_light(n, 4);
  c.reference = full_product(c.ptrs, n, map, c.b);
  return c;
}

TEST(DynamicTemporal, EstimateIsUnbiased) {
  const TemporalCase c = make_case(32, 3, {0, 1, 2});
  TemporalSettings settings;
  settings.samples_per_patch = 4;
  const TemporalRadiosity temporal(c.ptrs, c.n, c.map, settings);
  const int frames = 2000;
  std::vector<glm::dvec3> sum(c.n, glm::dvec3(0.0)), sum_sq(c.n, glm::dvec3(0.0));
  std::vector<glm::vec3> estimate;
  for (int f = 0; f < frames; ++f) {
    temporal.estimate(c.b, static_cast<std::uint32_t>(f), estimate);
    for (std::size_t p = 0; p < c.n; ++p) {
      const glm::dvec3 e(estimate[p]);
      sum[p] += e;
      sum_sq[p] += e * e;
    }
  }
  for (std::size_t p = 0; p < c.n; ++p)
    for (int k = 0; k < 3; ++k) {
      const double mean = sum[p][k] / frames;
      const double var = std::max(sum_sq[p][k] / frames - mean * mean, 0.0);
      const double standard_error = std::sqrt(var / frames);
      // 5 standard errors over 96 means: a false failure has probability ~1e-5.
      EXPECT_NEAR(mean, c.reference[p][k], 5.0 * standard_error + 1e-6 * c.reference[p][k])
          << "patch " << p << " colour " << k;
    }
}

double relative_error(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& ref) {
  double num = 0.0, den = 0.0;
  for (std::size_t p = 0; p < a.size(); ++p) {
    const glm::dvec3 d = glm::dvec3(a[p]) - glm::dvec3(ref[p]);
    num += glm::dot(d, d);
    den += glm::dot(glm::dvec3(ref[p]), glm::dvec3(ref[p]));
  }
  return std::sqrt(num / den);
}

TEST(DynamicTemporal, BlendConvergesToTheFullProduct) {
  const TemporalCase c = make_case(48, 1, {0, 0, 0});
  TemporalSettings settings;
  settings.samples_per_patch = 8;
  settings.history_weight = 0.99f;
  TemporalRadiosity temporal(c.ptrs, c.n, c.map, settings);
  // One frame's error e1 (expected squared error = the estimator's variance
  // V). The first 1/(1 - w) = 100 frames are a running mean (error^2 ~ V/f);
  // the steady state keeps (1 - w) / (1 + w) V. Allow 3x in the squared
  // error for the spread of one realisation.
  std::vector<glm::vec3> history;
  temporal.step(c.b, history);
  const double e1 = relative_error(history, c.reference);
  EXPECT_GT(e1, 0.0);
  for (int f = 1; f < 100; ++f) temporal.step(c.b, history);
  EXPECT_LT(relative_error(history, c.reference), e1 * std::sqrt(3.0 / 100.0));
  for (int f = 100; f < 1000; ++f) temporal.step(c.b, history);
  const double steady = e1 * std::sqrt(3.0 * (1.0 - 0.99) / (1.0 + 0.99));
  EXPECT_LT(relative_error(history, c.reference), steady);
  // A light that jumps: the old light decays as w^f.
  std::vector<glm::vec3> b2 = random_light(c.n, 99);
  for (auto& v : b2) v *= 3.0f;
  const std::vector<glm::vec3> reference2 = full_product(c.ptrs, c.n, c.map, b2);
  for (int f = 0; f < 700; ++f) temporal.step(b2, history);  // 0.99^700 < 1e-3
  EXPECT_LT(relative_error(history, reference2), 1.5 * steady + 2e-3);
}

TEST(DynamicTemporal, BlendWeightStartsAsRunningMean) {
  EXPECT_EQ(temporal_blend_weight(0.9f, 0), 0.0f);
  EXPECT_FLOAT_EQ(temporal_blend_weight(0.9f, 1), 0.5f);
  EXPECT_FLOAT_EQ(temporal_blend_weight(0.9f, 100), 0.9f);
}

TEST(DynamicTemporal, RejectsBadSettings) {
  const TemporalCase c = make_case(8, 1, {0, 0, 0});
  TemporalSettings s;
  s.samples_per_patch = 0;
  EXPECT_THROW(TemporalRadiosity(c.ptrs, c.n, c.map, s), Error);
  s = {};
  s.history_weight = 1.0f;
  EXPECT_THROW(TemporalRadiosity(c.ptrs, c.n, c.map, s), Error);
  EXPECT_THROW(TemporalRadiosity(c.ptrs, c.n, {0, 1, 0}, TemporalSettings{}), Error);
}

bool opencl_device(std::string& why) {
  try {
    OpenClContext::shared();
    return true;
  } catch (const Error& e) {
    why = e.what();
    return false;
  }
}

TEST(DynamicTemporal, OpenClMatchesCpp) {
  std::string why;
  if (!opencl_device(why)) GTEST_SKIP() << "no OpenCL device: " << why;
  for (int channels : {1, 3}) {
    const TemporalCase c = make_case(
        67, channels, channels == 1 ? std::array<int, 3>{0, 0, 0} : std::array<int, 3>{0, 1, 2});
    TemporalSettings settings;
    settings.samples_per_patch = 16;
    TemporalRadiosity cpu(c.ptrs, c.n, c.map, settings);
    ClTemporalRadiosity cl(cpu);
    std::vector<glm::vec3> history, cl_history, estimate, cl_estimate;
    for (int f = 0; f < 5; ++f) {
      cpu.step(c.b, history);
      cl.step(c.b);
    }
    cpu.estimate(c.b, 4, estimate);
    cl.read_history(cl_history);
    cl.read_estimate(cl_estimate);
    // Same samples, same summation order, FP_CONTRACT off: the only
    // difference allowed is the rounding of a different instruction choice,
    // a few ulps of the largest value.
    double scale = 0.0;
    for (const auto& v : history) scale = std::max<double>(scale, std::max({v.x, v.y, v.z}));
    for (std::size_t p = 0; p < c.n; ++p)
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(cl_history[p][k], history[p][k], 1e-6 * scale) << "patch " << p;
        EXPECT_NEAR(cl_estimate[p][k], estimate[p][k], 1e-6 * scale) << "patch " << p;
      }
    EXPECT_EQ(cl.frame(), 5u);
  }
}

// `bench dynamic`'s picture measures with a "camera" that shows patch i in
// pixel i (16 x 16 pixels, 256 patches of unit area): the picture's relative
// RMSE must then equal the patch error (area-weighted relative RMS) of the
// same frame; the full product's picture is its own (SSIM 1, error 0), and
// against a noise-free reference that is the full product of the scene's
// light it scores error 0 and SSIM 1, while temporal radiosity's picture
// gets closer from 1 to 64 frames.
TEST(DynamicBench, PictureMeasuresAgreeWithThePatchErrors) {
  const int side = 16;
  const std::size_t n = static_cast<std::size_t>(side * side);
  const TemporalCase c = make_case(n, 3, {0, 1, 2});
  const auto picture = [side](const std::vector<glm::vec3>& y) {
    RgbFloatImage image(side, side);
    image.pixels = y;
    return image;
  };
  DynamicBenchInput in;
  in.n = n;
  in.transport = c.ptrs;
  in.channel_of_rgb = c.map;
  in.albedo.assign(n, glm::vec3(0.5f));
  in.area.assign(n, 1.0f);
  in.light = c.b;
  in.jumped_light = random_light(n, 77);
  in.render_indirect = picture;
  in.scene_light = random_light(n, 5);
  in.reference_indirect = picture(full_product(c.ptrs, n, c.map, in.scene_light));
  in.reference_variance = RgbFloatImage(side, side);
  DynamicBenchSettings s;
  s.repeats = 1;
  s.local_matrix = false;
  s.temporal.samples_per_patch = 8;
  const DynamicBench b = run_dynamic_bench(in, s);
  EXPECT_EQ(b.image_width, side);
  EXPECT_EQ(b.reference_noise, 0.0);
  std::size_t measured = 0;
  for (const DynamicMethodRow& r : b.methods) {
    if (!r.available) continue;
    SCOPED_TRACE(r.method);
    ++measured;
    ASSERT_TRUE(r.images);
    ASSERT_TRUE(r.against_reference);
    for (std::size_t k = 0; k < 4; ++k)
      EXPECT_NEAR(r.image_error[k], r.error[k], 1e-5 * std::max(1.0, r.error[k])) << k;
  }
  EXPECT_GE(measured, 3u);  // full product, temporal C++, temporal through the graph
  const DynamicMethodRow& full = b.methods[0];
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_NEAR(full.image_ssim[k], 1.0, 1e-9);
    EXPECT_EQ(full.image_error[k], 0.0);
  }
  // float32 sgemv against the float64 sums of full_product().
  EXPECT_LT(full.reference_error, 1e-5);
  EXPECT_NEAR(full.reference_ssim, 1.0, 1e-6);
  const DynamicMethodRow& temporal = b.methods[1];
  EXPECT_LT(temporal.image_ssim[0], temporal.image_ssim[3]);
  EXPECT_LT(temporal.image_ssim[3], 1.0);
  EXPECT_GT(temporal.image_error[0], temporal.image_error[3]);
  EXPECT_GT(temporal.reference_error, 10.0 * full.reference_error);
}

}  // namespace
}  // namespace bounce
