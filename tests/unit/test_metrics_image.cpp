// Image and vertex metrics: SSIM against scikit-image's values on fixed image
// pairs (tests/data/ssim/make_ssim_values.py regenerates them), SSIM's
// analytic properties, and MSE / PSNR / relative RMSE against their formulas.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "base/error.h"
#include "metrics/image_metrics.h"
#include "metrics/vertex_metrics.h"

namespace bounce {
namespace {

// The same images as make_ssim_values.py builds.
std::vector<double> lcg_image(int width, int height, std::uint64_t seed) {
  std::vector<double> out;
  std::uint64_t state = seed;
  for (int i = 0; i < width * height; ++i) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    out.push_back(static_cast<double>(state >> 11) / 9007199254740992.0);
  }
  return out;
}

std::vector<double> pattern(int width, int height, double fx, double fy, double phase) {
  std::vector<double> out;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      out.push_back(0.5 + 0.4 * std::sin(fx * x + phase) * std::cos(fy * y));
  return out;
}

std::vector<double> axpb(const std::vector<double>& v, double a, double b) {
  std::vector<double> out(v);
  for (double& x : out) x = a * x + b;
  return out;
}

std::vector<double> add(const std::vector<double>& u, const std::vector<double>& v, double a,
                        double b, double c) {
  std::vector<double> out(u.size());
  for (std::size_t i = 0; i < u.size(); ++i) out[i] = a * u[i] + b * v[i] + c;
  return out;
}

// scikit-image 0.19.3 (Debian 12 python3-skimage), structural_similarity(x,
// y, gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
// data_range=L): tests/data/ssim/ssim_values.txt.
TEST(MetricsSsim, MatchesScikitImage) {
  const auto a = pattern(24, 20, 0.31, 0.23, 0.0);
  const auto a2 = add(a, pattern(24, 20, 0.7, 0.5, 1.0), 1.0, 0.1, -0.05);
  EXPECT_NEAR(mean_ssim(a, a2, 24, 20, 1.0), 0.98203675660750067, 1e-10);
  EXPECT_NEAR(mean_ssim(a, lcg_image(24, 20, 7), 24, 20, 1.0), -0.0021453681404400037, 1e-10);
  const auto n1 = lcg_image(17, 15, 1);
  const auto mixed = add(n1, lcg_image(17, 15, 2), 2.0 * 0.7, 2.0 * 0.3, 0.0);
  EXPECT_NEAR(mean_ssim(axpb(n1, 2.0, 0.0), mixed, 17, 15, 2.0), 0.87170160519182271, 1e-10);
  const auto s = pattern(12, 11, 0.9, 0.8, 0.3);
  EXPECT_NEAR(mean_ssim(s, axpb(s, 0.5, 0.0), 12, 11, 1.0), 0.64299789480842728, 1e-10);
  // Masked: the map averaged over the crop's pixels with x < 12.
  std::vector<std::uint8_t> left(24 * 20, 0);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 12; ++x) left[static_cast<std::size_t>(y * 24 + x)] = 1;
  EXPECT_NEAR(mean_ssim(a, a2, 24, 20, 1.0, left), 0.98273489750262422, 1e-10);
}

TEST(MetricsSsim, AnalyticProperties) {
  const auto a = pattern(20, 16, 0.4, 0.3, 0.2);
  const auto b = lcg_image(20, 16, 3);
  // Identical images: exactly 1.
  EXPECT_NEAR(mean_ssim(a, a, 20, 16, 1.0), 1.0, 1e-12);
  // Symmetric.
  EXPECT_NEAR(mean_ssim(a, b, 20, 16, 1.0), mean_ssim(b, a, 20, 16, 1.0), 1e-12);
  // A constant offset d changes only the luminance term: with equal local
  // variances and covariance, SSIM = (2 ux uy + C1) / (ux^2 + uy^2 + C1) per
  // pixel; for constant images ux = u, uy = u + d everywhere.
  const double u = 0.3, d = 0.2, c1 = 0.01 * 0.01;
  const std::vector<double> flat(20 * 16, u), lifted(20 * 16, u + d);
  EXPECT_NEAR(mean_ssim(flat, lifted, 20, 16, 1.0),
              (2 * u * (u + d) + c1) / (u * u + (u + d) * (u + d) + c1), 1e-12);
  // Contrast and structure of a textured image survive an offset: the map is
  // (2 ux (ux + d) + C1) / (ux^2 + (ux + d)^2 + C1) at every pixel, below 1.
  const double lifted_ssim = mean_ssim(a, axpb(a, 1.0, d), 20, 16, 1.0);
  EXPECT_LT(lifted_ssim, 1.0);
  EXPECT_GT(lifted_ssim, 0.5);
  EXPECT_THROW(mean_ssim(a, b, 20, 15, 1.0), Error);
  EXPECT_THROW(mean_ssim(a, b, 20, 16, 0.0), Error);
}

RgbFloatImage image_of(int w, int h, const std::vector<double>& values) {
  RgbFloatImage im(w, h);
  for (std::size_t i = 0; i < im.pixels.size(); ++i) {
    const auto v = static_cast<float>(values[i]);
    im.pixels[i] = {v, 0.5f * v, 0.25f * v};
  }
  return im;
}

TEST(MetricsImage, ErrorsFollowTheirDefinitions) {
  const int w = 16, h = 14;
  const RgbFloatImage ref = image_of(w, h, pattern(w, h, 0.4, 0.3, 0.0));
  RgbFloatImage test = ref;
  for (glm::vec3& p : test.pixels) p += glm::vec3(0.1f, 0.0f, -0.1f);
  const ImageErrors e = image_errors(test, ref);
  // Every pixel is off by 0.1 in two of three channels: MSE = 2/3 * 0.01.
  EXPECT_NEAR(e.mse, 0.02 / 3.0, 1e-8);
  EXPECT_NEAR(e.rmse, std::sqrt(0.02 / 3.0), 1e-8);
  double ref_sq = 0.0, peak = 0.0;
  for (const glm::vec3& p : ref.pixels)
    for (int c = 0; c < 3; ++c) {
      ref_sq += static_cast<double>(p[c]) * p[c];
      peak = std::max(peak, static_cast<double>(p[c]));
    }
  EXPECT_NEAR(e.relative_rmse, std::sqrt(0.02 * static_cast<double>(w * h) / ref_sq), 1e-6);
  EXPECT_NEAR(e.psnr, 10.0 * std::log10(peak * peak / (0.02 / 3.0)), 1e-5);
  EXPECT_EQ(e.pixels, static_cast<std::size_t>(w * h));
  const ImageErrors same = image_errors(ref, ref);
  EXPECT_EQ(same.mse, 0.0);
  EXPECT_TRUE(std::isinf(same.psnr));
  EXPECT_NEAR(same.ssim, 1.0, 1e-12);
}

TEST(MetricsImage, MaskLeavesTheBackgroundOut) {
  const int w = 16, h = 14;
  const RgbFloatImage ref = image_of(w, h, pattern(w, h, 0.4, 0.3, 0.0));
  RgbFloatImage test = ref;
  std::vector<std::uint8_t> mask(ref.pixels.size(), 1);
  // Wreck the left four columns and mask them out: no error remains.
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < 4; ++x) {
      test.at(x, y) = glm::vec3(9.0f);
      mask[ref.index(x, y)] = 0;
    }
  const ImageErrors e = image_errors(test, ref, mask);
  EXPECT_EQ(e.mse, 0.0);
  EXPECT_EQ(e.pixels, static_cast<std::size_t>((w - 4) * h));
  EXPECT_GT(image_errors(test, ref).mse, 1.0);
  EXPECT_THROW(image_errors(test, ref, std::vector<std::uint8_t>(3, 1)), Error);
  EXPECT_THROW(image_errors(test, ref, std::vector<std::uint8_t>(ref.pixels.size(), 0)), Error);
  EXPECT_THROW(image_errors(RgbFloatImage(3, 3), ref), Error);
}

TEST(MetricsImage, NoiseCorrectionRemovesTheReferencesOwnNoise) {
  // The truth is a pattern; the "reference" is the truth plus zero-mean
  // noise of known variance v (uniform on [-a, a]: v = a^2 / 3). A perfect
  // method (test = truth) then measures the noise as error, and the
  // correction takes it back out.
  const int w = 100, h = 100;
  const RgbFloatImage truth = image_of(w, h, pattern(w, h, 0.2, 0.1, 0.0));
  RgbFloatImage noisy = truth, variance(w, h);
  const auto noise = lcg_image(3 * w, h, 11);
  const double a = 0.1, v = a * a / 3.0;
  for (std::size_t i = 0; i < noisy.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      noisy.pixels[i][c] +=
          static_cast<float>(a * (2.0 * noise[3 * i + static_cast<std::size_t>(c)] - 1.0));
      variance.pixels[i][c] = static_cast<float>(v);
    }
  const double raw = image_errors(truth, noisy).relative_rmse;
  const double corrected = noise_corrected_relative_rmse(truth, noisy, variance);
  EXPECT_GT(raw, 0.05);
  // sum of squares of 30000 noise terms has relative spread sqrt(0.8 / 30000):
  // what is left is under 2% of the squared raw error, so under 15% of raw.
  EXPECT_LT(corrected, 0.15 * raw);
  // No variance: the plain relative RMSE; a real error survives the correction.
  EXPECT_NEAR(noise_corrected_relative_rmse(truth, noisy, RgbFloatImage(w, h)), raw, 1e-6);
  RgbFloatImage off = truth;
  for (glm::vec3& p : off.pixels) p *= 1.3f;
  const double wrong = image_errors(off, noisy).relative_rmse;
  EXPECT_NEAR(noise_corrected_relative_rmse(off, noisy, variance), 0.3, 0.02);
  EXPECT_GT(wrong, 0.3);
  // Vertices: the same formula.
  const std::vector<glm::vec3> t = {{1, 1, 1}, {2, 2, 2}}, r = {{1.1f, 1, 1}, {2, 2, 2}};
  EXPECT_NEAR(noise_corrected_relative_rmse(t, r, {{0.004f, 0, 0}, {0, 0, 0}}),
              std::sqrt((0.01 - 0.004) / (1.21 + 2 + 12)), 1e-6);
}

TEST(MetricsVertex, RelativeErrors) {
  const std::vector<glm::vec3> ref = {{1, 1, 1}, {2, 2, 2}, {0, 0, 0}};
  const std::vector<glm::vec3> test = {{1.1f, 1, 1}, {2, 2, 1.8f}, {0, 0, 0}};
  const VertexErrors e = vertex_errors(test, ref);
  EXPECT_NEAR(e.relative_rmse, std::sqrt((0.01 + 0.04) / 15.0), 1e-6);
  EXPECT_NEAR(e.max_relative, 0.1, 1e-6);
  EXPECT_NEAR(e.mean_relative, (0.1 + 0.1) / 9.0, 1e-6);
  EXPECT_EQ(e.vertices, 3u);
  EXPECT_EQ(vertex_errors(ref, ref).relative_rmse, 0.0);
  EXPECT_THROW(vertex_errors(test, {{1, 1, 1}}), Error);
}

}  // namespace
}  // namespace bounce
