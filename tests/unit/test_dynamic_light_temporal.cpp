// Temporal radiosity with importance on the light, read from the compressed
// matrix (dynamic/light_temporal_radiosity.h and its parts): systematic
// sampling hits each item draws * mass / total times on average; the block
// column product and the column sums agree with the decompressed matrix;
// the per-frame estimate is unbiased (the mean of many frames is T~ b within
// its standard error, and the same statistic does reject a 2% bias); the
// light change bounds the change of T~ b; and after a light jump the old
// light's share in the result obeys the ghosting bound of
// dynamic/adaptive_history.h, measured where the estimate is exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "base/error.h"
#include "compress/codec.h"
#include "compress/compressed_transport_tables.h"
#include "dynamic/adaptive_history.h"
#include "dynamic/compressed_columns.h"
#include "dynamic/light_temporal_radiosity.h"
#include "dynamic/systematic_draw.h"

namespace bounce {
namespace {

// Light exchange between random points on three walls of a box, one matrix
// per colour with its own scale (smooth in space, unordered in index).
std::vector<std::vector<float>> transport_like(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<glm::vec3> p(n);
  for (glm::vec3& x : p) {
    const int wall = static_cast<int>(u(rng) * 3.0f);
    x = wall == 0   ? glm::vec3(u(rng), u(rng), 0.0f)
        : wall == 1 ? glm::vec3(0.0f, u(rng), u(rng))
                    : glm::vec3(u(rng), 0.0f, u(rng));
  }
  std::vector<std::vector<float>> t(3, std::vector<float>(n * n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      const float base = i == j ? 0.0f : 0.01f * std::exp(-glm::length(p[i] - p[j]) / 0.3f);
      for (std::size_t c = 0; c < 3; ++c)
        t[c][i * n + j] = base * (1.0f - 0.2f * static_cast<float>(c)) * (1.0f + 0.2f * u(rng));
    }
  return t;
}

struct Compressed {
  CompressedMatrix m;
  CompressedTransportTables tables;
  std::vector<std::vector<float>> decoded;  // T~ per colour, n x n
};

Compressed compressed_transport(std::size_t n, unsigned seed) {
  const std::vector<std::vector<float>> t = transport_like(n, seed);
  Compressed c;
  c.m = compress_matrix({t[0].data(), t[1].data(), t[2].data()}, n, CodecSettings{});
  c.tables = build_compressed_transport_tables(c.m, {0, 1, 2});
  c.decoded.assign(3, std::vector<float>(n * n));
  for (int k = 0; k < 3; ++k)
    decompress_channel(c.m, k, c.decoded[static_cast<std::size_t>(k)].data());
  return c;
}

// A point-light-like b: a third of the patches lit, with strengths spread
// over two orders of magnitude.
std::vector<glm::vec3> point_light(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<glm::vec3> b(n, glm::vec3(0.0f));
  for (glm::vec3& v : b)
    if (u(rng) < 0.33f) v = std::pow(100.0f, u(rng)) * glm::vec3(1.0f, 0.7f, 0.3f + u(rng));
  return b;
}

std::vector<glm::dvec3> product(const Compressed& c, const std::vector<glm::vec3>& b) {
  const std::size_t n = b.size();
  std::vector<glm::dvec3> y(n, glm::dvec3(0.0));
  for (int k = 0; k < 3; ++k)
    for (std::size_t p = 0; p < n; ++p)
      for (std::size_t q = 0; q < n; ++q)
        y[p][k] += static_cast<double>(c.decoded[static_cast<std::size_t>(k)][p * n + q]) * b[q][k];
  return y;
}

double l1(const std::vector<glm::dvec3>& y) {
  double s = 0.0;
  for (const glm::dvec3& v : y) s += std::abs(v.x) + std::abs(v.y) + std::abs(v.z);
  return s;
}

TEST(SystematicDraw, HitsEachItemItsShareOnAverage) {
  const std::vector<double> mass{0.0, 3.0, 0.5, 0.0, 7.25, 0.01, 1.0, 2.0};
  const double total = std::accumulate(mass.begin(), mass.end(), 0.0);
  const int draws = 5;
  // Averaged over offsets u on a fine grid: hits / draws -> mass / total
  // (each item's hit count is a step function of u with at most 2 steps).
  const int grid = 20000;
  std::vector<double> weight(mass.size(), 0.0), hits(mass.size(), 0.0);
  SystematicDraw d;
  for (int g = 0; g < grid; ++g) {
    systematic_draw(mass, draws, (g + 0.5) / grid, d);
    int count = 0;
    for (std::size_t i = 0; i < d.items.size(); ++i) {
      const std::uint32_t j = d.items[i];
      ASSERT_GT(mass[j], 0.0);
      if (i > 0) {
        ASSERT_GT(j, d.items[i - 1]);
      }
      const double h = d.scale[i] * mass[j] * draws / total;
      ASSERT_NEAR(h, std::round(h), 1e-9);
      // floor or ceil of draws * share
      ASSERT_LE(std::abs(h - draws * mass[j] / total), 1.0);
      count += static_cast<int>(std::round(h));
      hits[j] += h;
      weight[j] += d.scale[i];
    }
    ASSERT_EQ(count, draws);
  }
  for (std::size_t j = 0; j < mass.size(); ++j) {
    EXPECT_NEAR(hits[j] / grid, draws * mass[j] / total, 2.0 / grid) << j;
    // The weight a sum receives from item j averages 1 where it has mass.
    EXPECT_NEAR(weight[j] / grid, mass[j] > 0.0 ? 1.0 : 0.0, 2.0 / grid * total / draws / 0.01)
        << j;
  }
  EXPECT_THROW(systematic_draw(mass, 0, 0.5, d), Error);
  EXPECT_THROW(systematic_draw(mass, 3, 1.0, d), Error);
  EXPECT_THROW(systematic_draw(std::vector<double>{1.0, -1.0}, 3, 0.5, d), Error);
  systematic_draw(std::vector<double>{0.0, 0.0}, 3, 0.5, d);
  EXPECT_TRUE(d.items.empty());
}

TEST(CompressedColumns, ProductAndColumnSumsMatchTheDecompressedMatrix) {
  const std::size_t n = 61;  // not a multiple of 4
  const Compressed c = compressed_transport(n, 3);
  ASSERT_GT(c.tables.corrections(), 0u);  // kept entries exercised
  const CompressedTransportTables& t = c.tables;
  const std::vector<glm::vec3> b = point_light(n, 4);
  // Every block column: the full product.
  std::vector<float> x(4 * t.padded, 0.0f);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) x[4 * i + static_cast<std::size_t>(k)] = b[t.permutation[i]][k];
  std::vector<std::uint32_t> all(t.block_rows);
  std::iota(all.begin(), all.end(), 0u);
  std::vector<float> y(4 * t.padded);
  const KeptColumns kept = kept_by_column(t);
  const std::vector<std::uint8_t> blocks = blocks_by_column(t);
  EXPECT_EQ(kept.row.size(), t.corrections());
  multiply_block_columns(t, blocks.data(), x.data(), all, reinterpret_cast<float(*)[4]>(y.data()));
  EXPECT_EQ(add_kept_columns(kept, x.data(), all, reinterpret_cast<float(*)[4]>(y.data())),
            t.corrections());
  const std::vector<glm::dvec3> ref = product(c, b);
  const double scale = l1(ref) / static_cast<double>(n);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(y[4 * i + static_cast<std::size_t>(k)], ref[t.permutation[i]][k], 1e-5 * scale);
  // Two block columns only: the product of b restricted to their patches.
  const std::vector<std::uint32_t> some{1, 7};
  std::vector<glm::vec3> restricted(n, glm::vec3(0.0f));
  for (std::uint32_t J : some)
    for (std::size_t i = 4 * J; i < 4 * J + 4 && i < n; ++i)
      restricted[t.permutation[i]] = b[t.permutation[i]];
  multiply_block_columns(t, blocks.data(), x.data(), some, reinterpret_cast<float(*)[4]>(y.data()));
  add_kept_columns(kept, x.data(), some, reinterpret_cast<float(*)[4]>(y.data()));
  const std::vector<glm::dvec3> part = product(c, restricted);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(y[4 * i + static_cast<std::size_t>(k)], part[t.permutation[i]][k], 1e-5 * scale);
  // Column sums of |T~|.
  const std::vector<float> sums = compressed_column_abs_sums(t);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t k = 0; k < 3; ++k) {
      double s = 0.0;
      for (std::size_t p = 0; p < n; ++p) s += std::abs(c.decoded[k][p * n + t.permutation[j]]);
      EXPECT_NEAR(sums[3 * j + k], s, 1e-5 * s + 1e-12) << j << " " << k;
    }
}

// Per patch and colour, the mean of F independent frames against T~ b in
// units of its standard error (sample standard deviation / sqrt(F)). With
// 3 n statistics, each ~N(0, 1) for an unbiased estimate, |z| <= 4.5 holds
// for all of them with probability ~1 - 3 n * 7e-6 (n = 64: 0.9987); the
// seeds are fixed, so the test is deterministic.
double worst_z(const std::vector<glm::dvec3>& sum, const std::vector<glm::dvec3>& sum_sq,
               int frames, const std::vector<glm::dvec3>& expected) {
  double worst = 0.0;
  for (std::size_t p = 0; p < sum.size(); ++p)
    for (int k = 0; k < 3; ++k) {
      const double mean = sum[p][k] / frames;
      const double var = (sum_sq[p][k] - frames * mean * mean) / (frames - 1);
      const double se = std::sqrt(std::max(var, 0.0) / frames);
      const double d = mean - expected[p][k];
      if (se > 0.0)
        worst = std::max(worst, std::abs(d) / se);
      else if (std::abs(d) > 1e-6 * std::abs(expected[p][k]) + 1e-12)
        worst = std::numeric_limits<double>::infinity();
    }
  return worst;
}

TEST(LightTemporalRadiosity, EstimateIsUnbiased) {
  const std::size_t n = 64;
  const Compressed c = compressed_transport(n, 5);
  const std::vector<glm::vec3> b = point_light(n, 6);
  const std::vector<glm::dvec3> exact = product(c, b);
  for (bool stratified : {false, true}) {
    LightTemporalSettings s;
    s.block_columns = 3;  // of 16: a noisy estimate, so that a bias would show
    s.stratify_frames = stratified;
    LightTemporalRadiosity light(c.tables, s);
    const int frames = 4000;
    std::vector<glm::dvec3> sum(n, glm::dvec3(0.0)), sum_sq(n, glm::dvec3(0.0));
    std::vector<glm::vec3> y(n);
    for (int f = 0; f < frames; ++f) {
      light.estimate(b, static_cast<std::uint32_t>(f), y);
      for (std::size_t p = 0; p < n; ++p) {
        sum[p] += glm::dvec3(y[p]);
        sum_sq[p] += glm::dvec3(y[p]) * glm::dvec3(y[p]);
      }
    }
    SCOPED_TRACE(stratified ? "stratified frames" : "independent frames");
    // Stratified frames are not independent: their mean is closer to T~ b
    // than independent frames' (the offsets cover [0, 1) evenly), so the
    // independent standard error is a conservative tolerance for it.
    EXPECT_LT(worst_z(sum, sum_sq, frames, exact), 4.5);
    if (!stratified) {
      // The statistic has the power to see a bias of 2%.
      std::vector<glm::dvec3> biased = exact;
      for (glm::dvec3& v : biased) v *= 0.98;
      EXPECT_GT(worst_z(sum, sum_sq, frames, biased), 4.5);
    }
  }
}

TEST(LightTemporalRadiosity, LightChangeBoundsTheChangeOfTheProduct) {
  const std::size_t n = 64;
  const Compressed c = compressed_transport(n, 7);
  LightTemporalRadiosity light(c.tables, LightTemporalSettings{});
  std::vector<glm::vec3> history(n, glm::vec3(0.0f));
  std::vector<glm::vec3> b = point_light(n, 8);
  EXPECT_EQ(light.light_change(b), 0.0);  // nothing before
  light.step(b, history);
  for (unsigned seed = 9; seed < 14; ++seed) {
    const std::vector<glm::vec3> next = point_light(n, seed);
    std::vector<glm::vec3> mixed(n);
    for (std::size_t p = 0; p < n; ++p) mixed[p] = 0.8f * b[p] + 0.2f * next[p];
    const double change = light.light_change(mixed);
    std::vector<glm::vec3> diff(n);
    for (std::size_t p = 0; p < n; ++p) diff[p] = mixed[p] - b[p];
    const double actual = l1(product(c, diff)) / l1(product(c, mixed));
    EXPECT_GT(change, 0.0);
    EXPECT_LE(actual, change * (1.0 + 1e-5));
  }
  EXPECT_EQ(light.light_change(b), 0.0);
  EXPECT_THROW(light.light_change(std::vector<glm::vec3>(n - 1)), Error);
}

// Four patches are one block column, drawn every frame with weight 1: the
// estimate is exact, and what the result keeps of the old light after a jump
// is the blend alone. Its L1 error against the new light's product, relative
// to the light, must stay under ghosting_bound(change).
TEST(LightTemporalRadiosity, GhostingStaysUnderItsBound) {
  const std::size_t n = 4;
  const Compressed c = compressed_transport(n, 15);
  LightTemporalSettings s;
  s.block_columns = 2;
  s.history.change_scale = 0.5;
  s.history.max_frames = 32;
  const std::vector<glm::vec3> before{
      {1.0f, 1.0f, 1.0f}, {0.0f, 0.0f, 0.0f}, {2.0f, 1.0f, 0.5f}, {0.5f, 0.5f, 0.5f}};
  const std::vector<glm::vec3> other{
      {0.0f, 0.0f, 0.0f}, {3.0f, 2.0f, 1.0f}, {0.0f, 0.5f, 1.0f}, {0.5f, 0.5f, 0.5f}};
  int checked = 0;
  for (float t : {0.02f, 0.05f, 0.1f, 0.2f, 0.3f, 0.5f, 1.0f}) {
    LightTemporalRadiosity light(c.tables, s);
    std::vector<glm::vec3> history(n, glm::vec3(0.0f));
    for (int f = 0; f < 40; ++f) light.step(before, history);  // steady: history = T~ b exactly
    ASSERT_EQ(light.history_frames(), static_cast<double>(s.history.max_frames));
    std::vector<glm::vec3> after(n);
    for (std::size_t p = 0; p < n; ++p) after[p] = (1.0f - t) * before[p] + t * other[p];
    light.step(after, history);
    const double change = light.last_change();
    ASSERT_GT(change, 0.0);
    EXPECT_LE(light.last_weight(), std::max(0.0, 1.0 - change / s.history.change_scale) + 1e-6);
    const std::vector<glm::dvec3> exact = product(c, after);
    std::vector<glm::dvec3> error(n);
    for (std::size_t p = 0; p < n; ++p) error[p] = glm::dvec3(history[p]) - exact[p];
    // Relative to sum c |b|, which is >= ||T~ b||_1 for T~ >= 0.
    double light_l1 = 0.0;
    const std::vector<float> sums = compressed_column_abs_sums(c.tables);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < 3; ++k)
        light_l1 += sums[3 * i + k] * std::abs(after[c.tables.permutation[i]][static_cast<int>(k)]);
    const double ghost = l1(error) / light_l1;
    EXPECT_LE(ghost, ghosting_bound(change, s.history.change_scale) + 1e-5) << "t " << t;
    if (change >= s.history.change_scale) {
      EXPECT_EQ(light.last_weight(), 0.0f);  // forgotten at once
      EXPECT_LT(ghost, 1e-5);
    }
    ++checked;
  }
  EXPECT_EQ(checked, 7);
}

TEST(LightTemporalRadiosity, SteadyLightAveragesUpToTheCap) {
  const std::size_t n = 16;
  const Compressed c = compressed_transport(n, 16);
  LightTemporalSettings s;
  s.history.max_frames = 5;
  LightTemporalRadiosity light(c.tables, s);
  const std::vector<glm::vec3> b = point_light(n, 17);
  std::vector<glm::vec3> history(n, glm::vec3(0.0f));
  for (int f = 0; f < 8; ++f) {
    light.step(b, history);
    EXPECT_FLOAT_EQ(light.last_weight(), history_weight(std::min(f, 5)));
    EXPECT_EQ(light.last_change(), 0.0);
  }
  light.reset();
  light.step(b, history);
  EXPECT_EQ(light.last_weight(), 0.0f);
  EXPECT_THROW(light.step(b, std::span<glm::vec3>(history.data(), n - 1)), Error);
  EXPECT_THROW(light.estimate(std::vector<glm::vec3>(n + 1), 0, history), Error);
  LightTemporalSettings bad;
  bad.block_columns = 0;
  EXPECT_THROW(LightTemporalRadiosity(c.tables, bad), Error);
  bad = LightTemporalSettings{};
  bad.history.change_scale = 0.0;
  EXPECT_THROW(LightTemporalRadiosity(c.tables, bad), Error);
}

}  // namespace
}  // namespace bounce
