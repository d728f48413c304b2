#include "metrics/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "base/error.h"

namespace bounce {

namespace {

constexpr double kSigma = 1.5;
constexpr int kRadius = 5;  // int(3.5 * sigma + 0.5): scipy's truncate = 3.5, an 11 x 11 window
constexpr double kK1 = 0.01, kK2 = 0.03;

// Index into [0, n) with the edge mirrored and the edge sample repeated
// (d c b a | a b c d), scipy.ndimage's "reflect", also for n < radius.
int reflect(int i, int n) {
  const int period = 2 * n;
  i %= period;
  if (i < 0) i += period;
  return i < n ? i : period - 1 - i;
}

std::vector<double> gaussian_weights() {
  std::vector<double> w(2 * kRadius + 1);
  double sum = 0.0;
  for (int k = -kRadius; k <= kRadius; ++k)
    sum += w[static_cast<std::size_t>(k + kRadius)] = std::exp(-0.5 * k * k / (kSigma * kSigma));
  for (double& v : w) v /= sum;
  return w;
}

// Separable Gaussian blur: rows (axis 0, y) first, then columns, as scipy's
// gaussian_filter does axis by axis.
std::vector<double> blur(const std::vector<double>& in, int width, int height) {
  static const std::vector<double> w = gaussian_weights();
  const auto at = [width](int x, int y) {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
           static_cast<std::size_t>(x);
  };
  std::vector<double> tmp(in.size()), out(in.size());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double s = 0.0;
      for (int k = -kRadius; k <= kRadius; ++k)
        s += w[static_cast<std::size_t>(k + kRadius)] * in[at(x, reflect(y + k, height))];
      tmp[at(x, y)] = s;
    }
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double s = 0.0;
      for (int k = -kRadius; k <= kRadius; ++k)
        s += w[static_cast<std::size_t>(k + kRadius)] * tmp[at(reflect(x + k, width), y)];
      out[at(x, y)] = s;
    }
  return out;
}

void check_sizes(std::size_t a, std::size_t b, int width, int height) {
  if (width < 1 || height < 1) throw Error("image metrics", "images must be at least 1 x 1 pixel");
  const auto n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (a != n || b != n)
    throw Error("image metrics", "images of different size (" + std::to_string(a) + " and " +
                                     std::to_string(b) + " pixels, expected " + std::to_string(n) +
                                     ")");
}

}  // namespace

std::vector<double> luminance(const RgbFloatImage& image) {
  std::vector<double> y(image.pixels.size());
  for (std::size_t i = 0; i < y.size(); ++i) {
    const glm::vec3& p = image.pixels[i];
    y[i] = 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
  }
  return y;
}

std::vector<double> ssim_map(const std::vector<double>& x, const std::vector<double>& y, int width,
                             int height, double data_range) {
  check_sizes(x.size(), y.size(), width, height);
  if (!(data_range > 0.0)) throw Error("SSIM", "the data range must be positive");
  std::vector<double> xx(x.size()), yy(x.size()), xy(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    xx[i] = x[i] * x[i];
    yy[i] = y[i] * y[i];
    xy[i] = x[i] * y[i];
  }
  const std::vector<double> ux = blur(x, width, height), uy = blur(y, width, height),
                            uxx = blur(xx, width, height), uyy = blur(yy, width, height),
                            uxy = blur(xy, width, height);
  const double c1 = (kK1 * data_range) * (kK1 * data_range);
  const double c2 = (kK2 * data_range) * (kK2 * data_range);
  std::vector<double> s(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double vx = uxx[i] - ux[i] * ux[i], vy = uyy[i] - uy[i] * uy[i];
    const double vxy = uxy[i] - ux[i] * uy[i];
    s[i] = ((2.0 * ux[i] * uy[i] + c1) * (2.0 * vxy + c2)) /
           ((ux[i] * ux[i] + uy[i] * uy[i] + c1) * (vx + vy + c2));
  }
  return s;
}

double mean_ssim(const std::vector<double>& x, const std::vector<double>& y, int width, int height,
                 double data_range, const std::vector<std::uint8_t>& mask) {
  const std::vector<double> s = ssim_map(x, y, width, height, data_range);
  if (!mask.empty() && mask.size() != s.size())
    throw Error("SSIM", "the mask has " + std::to_string(mask.size()) + " pixels, the images " +
                            std::to_string(s.size()));
  double sum = 0.0;
  std::size_t n = 0;
  for (int j = kRadius; j < height - kRadius; ++j)
    for (int i = kRadius; i < width - kRadius; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(width) +
                            static_cast<std::size_t>(i);
      if (!mask.empty() && !mask[k]) continue;
      sum += s[k];
      ++n;
    }
  if (n == 0)
    throw Error("SSIM",
                "no pixel to compare (images under 11 x 11, or the mask is empty inside "
                "the 5-pixel border)");
  return sum / static_cast<double>(n);
}

ImageErrors image_errors(const RgbFloatImage& test, const RgbFloatImage& reference,
                         const std::vector<std::uint8_t>& mask, double data_range) {
  if (test.width != reference.width || test.height != reference.height)
    throw Error("image metrics", "images of different size: " + std::to_string(test.width) + "x" +
                                     std::to_string(test.height) + " and " +
                                     std::to_string(reference.width) + "x" +
                                     std::to_string(reference.height));
  check_sizes(test.pixels.size(), reference.pixels.size(), reference.width, reference.height);
  if (!mask.empty() && mask.size() != reference.pixels.size())
    throw Error("image metrics", "the mask has " + std::to_string(mask.size()) +
                                     " pixels, the images " +
                                     std::to_string(reference.pixels.size()));
  ImageErrors e;
  double sq = 0.0, ref_sq = 0.0, peak = 0.0, peak_y = 0.0;
  const std::vector<double> ty = luminance(test), ry = luminance(reference);
  for (std::size_t i = 0; i < reference.pixels.size(); ++i) {
    if (!mask.empty() && !mask[i]) continue;
    ++e.pixels;
    for (int c = 0; c < 3; ++c) {
      const double x = test.pixels[i][c], y = reference.pixels[i][c];
      sq += (x - y) * (x - y);
      ref_sq += y * y;
      peak = std::max(peak, y);
    }
    peak_y = std::max(peak_y, ry[i]);
  }
  if (e.pixels == 0) throw Error("image metrics", "the mask selects no pixel");
  e.mse = sq / (3.0 * static_cast<double>(e.pixels));
  e.rmse = std::sqrt(e.mse);
  e.relative_rmse = ref_sq > 0.0 ? std::sqrt(sq / ref_sq) : std::numeric_limits<double>::infinity();
  const double range = data_range > 0.0 ? data_range : peak;
  e.psnr = e.mse > 0.0 ? 10.0 * std::log10(range * range / e.mse)
                       : std::numeric_limits<double>::infinity();
  const double range_y = data_range > 0.0 ? data_range : peak_y;
  e.ssim = range_y > 0.0 ? mean_ssim(ty, ry, reference.width, reference.height, range_y, mask)
                         : std::numeric_limits<double>::quiet_NaN();
  return e;
}

double noise_corrected_relative_rmse(const RgbFloatImage& test, const RgbFloatImage& reference,
                                     const RgbFloatImage& reference_variance,
                                     const std::vector<std::uint8_t>& mask) {
  const std::size_t n = reference.pixels.size();
  if (test.pixels.size() != n || reference_variance.pixels.size() != n ||
      (!mask.empty() && mask.size() != n))
    throw Error("image metrics", "test, reference, variance and mask differ in size");
  double sq = 0.0, var = 0.0, ref_sq = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!mask.empty() && !mask[i]) continue;
    for (int c = 0; c < 3; ++c) {
      const double x = test.pixels[i][c], y = reference.pixels[i][c];
      sq += (x - y) * (x - y);
      var += reference_variance.pixels[i][c];
      ref_sq += y * y;
    }
  }
  if (!(ref_sq > 0.0)) return std::numeric_limits<double>::infinity();
  return std::sqrt(std::max(0.0, sq - var) / ref_sq);
}

std::vector<std::uint8_t> mask_from_coverage(const std::vector<float>& coverage) {
  std::vector<std::uint8_t> m(coverage.size());
  for (std::size_t i = 0; i < m.size(); ++i) m[i] = coverage[i] > 0.0f ? 1 : 0;
  return m;
}

}  // namespace bounce
