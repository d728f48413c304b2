#pragma once
// How far a picture is from its reference, on the pixels both show (a mask
// leaves out the background, which is exactly zero in both and would make
// any method look good). Definitions (docs/reference.md):
//   MSE           mean over masked pixels and the R, G, B channels of (x - y)^2
//   RMSE          sqrt(MSE)
//   relative RMSE sqrt(sum (x - y)^2 / sum y^2): RMSE in units of the
//                 reference's own RMS level, so scenes of any brightness compare
//   PSNR          10 log10(peak^2 / MSE), peak = data range (below)
//   SSIM          Wang, Bovik, Sheikh, Simoncelli 2004 on the luminance
//                 Y = 0.2126 R + 0.7152 G + 0.0722 B (Rec. 709), Gaussian window
//                 11 x 11 with sigma 1.5, K1 = 0.01, K2 = 0.03, population
//                 (not sample) covariances, the image edges mirrored ("reflect"
//                 as scipy does it) -- scikit-image's structural_similarity(...,
//                 gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
//                 data_range=L), whose map it averages over the pixels at least
//                 5 from the border; here, over those that are also in the mask.
// The data range L (peak) defaults to the reference's largest masked value
// (per channel for PSNR, luminance for SSIM).
#include <cstdint>
#include <vector>

#include "io/exr_writer.h"

namespace bounce {

struct ImageErrors {
  double mse = 0.0, rmse = 0.0, relative_rmse = 0.0, psnr = 0.0, ssim = 0.0;
  std::size_t pixels = 0;  // masked pixels compared
};

// Rec. 709 luminance of every pixel.
std::vector<double> luminance(const RgbFloatImage& image);

// The SSIM map of two single-channel images (width x height, row-major) with
// data range L; throws bounce::Error when sizes differ or L <= 0.
std::vector<double> ssim_map(const std::vector<double>& x, const std::vector<double>& y, int width,
                             int height, double data_range);

// Mean SSIM over the pixels at least 5 from the border (and in `mask` when
// it is non-empty: 1 = compare).
double mean_ssim(const std::vector<double>& x, const std::vector<double>& y, int width, int height,
                 double data_range, const std::vector<std::uint8_t>& mask = {});

// All metrics of `test` against `reference` on the masked pixels (empty
// mask: every pixel). data_range <= 0: the reference's largest masked value.
// Throws bounce::Error for images of different size or a mask of wrong size.
ImageErrors image_errors(const RgbFloatImage& test, const RgbFloatImage& reference,
                         const std::vector<std::uint8_t>& mask = {}, double data_range = 0.0);

// Relative RMSE against the noise-free image the reference estimates: a Monte
// Carlo reference y^ = y + noise adds its variance to every squared error,
// E[(x - y^)^2] = (x - y)^2 + var(y^), so
//   sqrt(max(0, sum (x - y^)^2 - sum var) / sum y^2)
// removes the reference's own noise using its per-pixel variance of the mean
// (unbiased in the numerator; 0 when the difference is all noise).
double noise_corrected_relative_rmse(const RgbFloatImage& test, const RgbFloatImage& reference,
                                     const RgbFloatImage& reference_variance,
                                     const std::vector<std::uint8_t>& mask = {});

// Mask of the pixels a renderer saw geometry in (coverage > 0).
std::vector<std::uint8_t> mask_from_coverage(const std::vector<float>& coverage);

}  // namespace bounce
