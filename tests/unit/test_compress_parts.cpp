// The pieces of the compression pipeline that do not depend on a block
// format: the log quantiser, the kept-entry split, the error figures and the
// matrix pictures.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "compress/compression_error.h"
#include "compress/log_quantizer.h"
#include "compress/matrix_error.h"
#include "compress/matrix_picture.h"
#include "compress/sparse_split.h"
#include "scratch_dir.h"

namespace bounce {

TEST(LogQuantizer, RoundTripWithinHalfACodeStep) {
  const LogQuantizer q{2.0f, 25.0f};
  // Half a code step is a relative error of exp(R / 510) - 1 = 5.0%.
  const double half_step = std::exp(25.0 / 510.0) - 1.0;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> exponent(-25.0, 0.0);
  for (int k = 0; k < 10000; ++k) {
    const auto v = static_cast<float>(2.0 * std::exp(exponent(rng)));
    const float back = q.decode(q.encode(v));
    if (v < 2.0f * std::exp(-25.0f + 25.0f / 510.0f)) continue;  // rounds to code 0
    EXPECT_NEAR(back / v, 1.0, half_step * 1.001) << v;
  }
  EXPECT_EQ(q.encode(0.0f), 0);
  EXPECT_EQ(q.decode(0), 0.0f);
  EXPECT_EQ(q.encode(2.0f), 255);
  EXPECT_FLOAT_EQ(q.decode(255), 2.0f);
  EXPECT_EQ(q.encode(1e-30f), 0);  // below vmax e^-25
}

TEST(SparseSplit, KeepsTheLargestFractionExactly) {
  const std::size_t n = 50;
  std::vector<float> m(n * n);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (auto& v : m) v = u(rng);
  m[7] = 0.0f;
  const float t = kept_threshold(m.data(), n, 0.04);
  const CsrMatrix kept = extract_kept(m.data(), n, t);
  EXPECT_EQ(kept.value.size(), 100u);  // 4% of 2500, no ties in random floats
  std::vector<float> sorted(m);
  std::sort(sorted.begin(), sorted.end(), std::greater<float>());
  EXPECT_EQ(t, sorted[99]);
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t k = kept.row_ptr[i]; k < kept.row_ptr[i + 1]; ++k)
      EXPECT_EQ(kept.value[k], m[i * n + kept.col[k]]);  // exact, bit for bit
  EXPECT_EQ(extract_kept(m.data(), n, kept_threshold(m.data(), n, 0.0)).value.size(), 0u);
}

// Values over many decades (as T's entries are), with ties, zeros, negatives
// and a NaN, on a subset of rows: the threshold is the k-th largest positive
// value of those rows, as a sort gives it, for every fraction.
TEST(SparseSplit, ThresholdIsTheKthLargestPositiveOfTheRows) {
  const std::size_t n = 97;
  std::vector<float> m(n * n);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-30.0f, 2.0f);
  for (auto& v : m) v = std::exp(u(rng));
  for (std::size_t k = 0; k < m.size(); k += 13) m[k] = m[k / 2];  // ties
  for (std::size_t k = 5; k < m.size(); k += 17) m[k] = 0.0f;
  for (std::size_t k = 9; k < m.size(); k += 29) m[k] = -m[k];
  m[3] = std::numeric_limits<float>::quiet_NaN();
  std::vector<std::uint32_t> rows;
  for (std::uint32_t i = 0; i < n; i += 3) rows.push_back(i);
  std::vector<float> positive;
  for (const std::uint32_t i : rows)
    for (std::size_t j = 0; j < n; ++j)
      if (m[i * n + j] > 0.0f) positive.push_back(m[i * n + j]);
  std::sort(positive.begin(), positive.end(), std::greater<float>());
  for (const double fraction : {0.0001, 0.0004, 0.003, 0.01, 0.04, 0.3, 0.7, 0.85, 1.0}) {
    const auto keep =
        static_cast<std::size_t>(std::llround(fraction * static_cast<double>(rows.size() * n)));
    const float expected = keep == 0                 ? std::numeric_limits<float>::infinity()
                           : keep >= positive.size() ? std::numeric_limits<float>::min()
                                                     : positive[keep - 1];
    EXPECT_EQ(kept_threshold(m.data(), n, rows, fraction), expected) << fraction;
  }
  EXPECT_EQ(kept_threshold(m.data(), n, rows, 0.0), std::numeric_limits<float>::infinity());
}

TEST(MatrixError, FiguresMatchADirectComputation) {
  const std::vector<float> exact = {1.0f, 2.0f, 0.0f, 4.0f};
  const std::vector<float> approx = {1.5f, 2.0f, 0.25f, 3.0f};
  MatrixErrorAccumulator acc;
  acc.add(exact.data(), approx.data(), 2);
  acc.add(exact.data() + 2, approx.data() + 2, 2);
  const MatrixError e = acc.result();
  EXPECT_DOUBLE_EQ(e.sum_abs, 0.5 + 0.0 + 0.25 + 1.0);
  EXPECT_DOUBLE_EQ(e.mean_abs, 1.75 / 4.0);
  EXPECT_DOUBLE_EQ(e.max_abs, 1.0);
  EXPECT_NEAR(e.rel_frobenius, std::sqrt((0.25 + 0.0625 + 1.0) / (1.0 + 4.0 + 16.0)), 1e-12);
}

TEST(MatrixPicture, LogColoursZerosBlackAndAColourBar) {
  const std::size_t n = 64;
  std::vector<float> m(n * n, 0.0f);
  for (std::size_t i = 0; i < n; ++i) m[i * n + i] = 1.0f;           // diagonal: max
  for (std::size_t i = 0; i + 1 < n; ++i) m[i * n + i + 1] = 1e-3f;  // 3 decades down
  MatrixPictureSettings s;
  s.decades = 6.0;
  const Rgb8Image img = matrix_picture(m.data(), n, s);
  const int margin = 4;
  std::uint8_t top[3], mid[3];
  colormap(1.0, top);
  colormap(0.5, mid);
  const std::uint8_t* diag = const_cast<Rgb8Image&>(img).at(margin + 10, margin + 10);
  const std::uint8_t* upper = const_cast<Rgb8Image&>(img).at(margin + 11, margin + 10);
  const std::uint8_t* zero = const_cast<Rgb8Image&>(img).at(margin + 40, margin + 10);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(diag[c], top[c]);
    EXPECT_EQ(upper[c], mid[c]);
    EXPECT_EQ(zero[c], 0);
  }
  // Permuted picture: reversing the order keeps the diagonal on the diagonal.
  std::vector<std::uint32_t> reverse(n);
  for (std::size_t i = 0; i < n; ++i) reverse[i] = static_cast<std::uint32_t>(n - 1 - i);
  const Rgb8Image flipped = matrix_picture(m.data(), n, s, &reverse);
  const std::uint8_t* d2 = const_cast<Rgb8Image&>(flipped).at(margin + 10, margin + 10);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(d2[c], top[c]);
  // And it survives a PNG round trip.
  const test::ScratchDir dir("bounce-matrix-picture");
  const auto path = dir / "picture.png";
  write_png(path, img);
  const Rgb8Image back = read_png(path);
  EXPECT_EQ(back.width, img.width);
  EXPECT_EQ(back.pixels, img.pixels);
}

TEST(IndirectLightError, ScaledMatrixGivesTheScaleAsRelativeError) {
  // T~ = 1.1 T for one channel, 0.8 T for another: I~ - I = 0.1 I or -0.2 I
  // per channel, so the relative RMS is sqrt((0.01 a + 0.04 b) / (a + b)),
  // a, b the weighted squared norms of the two channels' indirect light.
  const std::size_t n = 5;
  std::vector<float> t(n * n), up(n * n), down(n * n);
  for (std::size_t k = 0; k < n * n; ++k) {
    t[k] = 0.01f * static_cast<float>(k % 7 + 1);
    up[k] = 1.1f * t[k];
    down[k] = 0.8f * t[k];
  }
  IndirectLightProbe probe;
  probe.channel_of_rgb = {0, 0, 1};  // R and G share matrix 0, B has matrix 1
  probe.area = {1.0f, 2.0f, 1.0f, 0.5f, 1.0f};
  probe.first_hit.push_back(std::vector<glm::vec3>(n, glm::vec3(1.0f)));
  probe.first_hit.push_back(std::vector<glm::vec3>(n, glm::vec3(0.0f)));  // dark: skipped
  const IndirectLightError e =
      indirect_light_error({t.data(), t.data()}, {up.data(), down.data()}, n, probe);
  EXPECT_EQ(e.lights, 1u);
  // b = 1 everywhere: every channel's indirect light is the row sums of T.
  double a = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    double row = 0.0;
    for (std::size_t q = 0; q < n; ++q) row += t[p * n + q];
    a += probe.area[p] * row * row;
  }
  const double expected = std::sqrt((2 * 0.01 * a + 0.04 * a) / (3 * a));
  EXPECT_NEAR(e.rel_rms_mean, expected, 1e-6);
  EXPECT_NEAR(e.rel_rms_max, expected, 1e-6);
}

TEST(LogQuantizer, FittedRangeCoversTheValuesAndNoMore) {
  // Values log-uniform over 8 e-folds below vmax = 2: ln(vmax / v) is uniform
  // on [0, 8], so its 0.1% lowest-value quantile sits at 8 * 0.999.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 8.0);
  std::vector<float> v(200000);
  for (float& x : v) x = static_cast<float>(2.0 * std::exp(-u(rng)));
  v[7] = 0.0f;  // zeros do not count
  const float range = fitted_log_range(v.data(), v.size(), 2.0f, 0.001);
  EXPECT_NEAR(range, 8.0 * 0.999, 0.02);
  // A narrower range means finer codes: the round trip error of a value in
  // range is at most half a step, range / 510 relative; none becomes 0.
  LogQuantizer q;
  q.vmax = 2.0f;
  q.range = range;
  q.nearest_at_zero = true;
  for (std::size_t k = 0; k < 1000; ++k) {
    if (v[k] < 2.0f * std::exp(-range)) continue;
    // Below code 1 the nearest non-zero code is 1, up to one whole step away.
    const double steps = v[k] < q.decode(1) ? 255.0 : 510.0;
    EXPECT_NEAR(q.decode(q.encode(v[k])), v[k], v[k] * (std::exp(range / steps) - 1.0) * 1.001);
  }
  // Never wider than the paper's 25, never narrower than 1.
  std::vector<float> flat(100, 1.0f);
  EXPECT_EQ(fitted_log_range(flat.data(), flat.size(), 1.0f, 0.001), 1.0f);
  std::vector<float> wide{1.0f, 1e-20f, 1e-20f, 1e-20f};
  EXPECT_EQ(fitted_log_range(wide.data(), wide.size(), 1.0f, 0.5), 25.0f);
}

TEST(MatrixPicture, ColourBarValuesAndCaptionAreDrawn) {
  const std::size_t n = 200;
  std::vector<float> m(n * n, 1e-3f);
  MatrixPictureSettings s;
  const Rgb8Image plain = matrix_picture(m.data(), n, s);
  s.title = "caption";
  const Rgb8Image titled = matrix_picture(m.data(), n, s);
  EXPECT_GT(titled.height, plain.height) << "no room made for the caption";
  // Dark text pixels on the white background right of the colour bar (the
  // labels) and above the matrix (the caption).
  auto dark_pixels = [](Rgb8Image& img, int x0, int x1, int y0, int y1) {
    int count = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) count += img.at(x, y)[0] < 100 && img.at(x, y)[1] < 100;
    return count;
  };
  Rgb8Image t = titled;
  const int margin = 4, bar_right = margin + 200 + 8 + 12;
  EXPECT_GT(dark_pixels(t, bar_right, t.width, 0, t.height), 50) << "no colour-bar labels";
  EXPECT_GT(dark_pixels(t, 0, 200, 0, titled.height - plain.height + margin), 20) << "no caption";
}

}  // namespace bounce
