// The error maps of a compressed matrix as the studio's error view shows them
// (compress/compression_error_maps.h), against the computations the view
// made itself before they moved into the core: the same numbers and pixels.
#include <gtest/gtest.h>

#include "base/error.h"
#include "compress/compression_error_maps.h"
#include "compress/matrix_picture.h"
#include "compressed_cornell_bake.h"

namespace bounce {
namespace {

void expect_same_picture(const Rgb8Image& a, const Rgb8Image& b, const char* what) {
  EXPECT_EQ(a.width, b.width) << what;
  EXPECT_EQ(a.height, b.height) << what;
  EXPECT_TRUE(a.pixels == b.pixels) << what;
}

TEST(CompressionErrorMaps, SameNumbersAndPicturesAsTheViewMadeThem) {
  const LoadedBake& b = test::compressed_cornell_bake();
  ASSERT_TRUE(b.compressed);
  const CompressedMatrix& c = *b.compressed;
  const std::size_t n = b.size();
  std::vector<const float*> exact;
  for (const auto& m : b.dense) exact.push_back(m.data());
  std::vector<float> abs_error;
  const CompressionErrors errors = measure_compression(exact, c, b.probe, &abs_error);
  constexpr int kSize = 512;
  const CompressionErrorMaps maps = compression_error_maps(exact, n, c, errors, abs_error, kSize);

  EXPECT_EQ(maps.errors.matrix.sum_abs, errors.matrix.sum_abs);
  EXPECT_EQ(maps.abs_error, abs_error);
  // The means over stored channels, summed in the view's order.
  std::vector<float> exact_mean(n * n, 0.0f), decoded_mean(n * n, 0.0f), decoded(n * n);
  const float scale = 1.0f / static_cast<float>(c.channels);
  for (int ch = 0; ch < c.channels; ++ch) {
    decompress_channel(c, ch, decoded.data());
    const std::vector<float>& t = b.dense[static_cast<std::size_t>(ch)];
    for (std::size_t k = 0; k < n * n; ++k) {
      exact_mean[k] += t[k] * scale;
      decoded_mean[k] += decoded[k] * scale;
    }
  }
  EXPECT_EQ(maps.exact_mean, exact_mean);
  EXPECT_EQ(maps.decoded_mean, decoded_mean);
  EXPECT_NE(maps.exact_mean, maps.decoded_mean);

  MatrixPictureSettings s;
  s.max_size = kSize;
  s.title = "|T~ - T| per entry, reordered (" + c.ordering + ")";
  EXPECT_EQ(maps.entry_title, s.title);
  expect_same_picture(maps.entry_picture, matrix_picture(abs_error.data(), n, s, &c.permutation),
                      "per entry");
  std::vector<float> stored(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      stored[i * n + j] = abs_error[c.permutation[i] * n + c.permutation[j]];
  std::size_t blocks = 0;
  const std::vector<float> sums = block_error_sums(stored.data(), n, blocks);
  EXPECT_EQ(maps.blocks, blocks);
  EXPECT_EQ(maps.blocks, (n + 3) / 4);
  EXPECT_EQ(maps.block_sums, sums);
  s.title = "|T~ - T| per 4x4 block of T.dds (" + c.codec + ")";
  EXPECT_EQ(maps.block_title, s.title);
  expect_same_picture(maps.block_picture, matrix_picture(sums.data(), blocks, s), "per block");
}

TEST(CompressionErrorMaps, RefusesMatricesThatDoNotFit) {
  const LoadedBake& b = test::compressed_cornell_bake();
  const std::size_t n = b.size();
  std::vector<const float*> exact;
  for (const auto& m : b.dense) exact.push_back(m.data());
  std::vector<float> abs_error;
  const CompressionErrors errors = measure_compression(exact, *b.compressed, b.probe, &abs_error);
  EXPECT_THROW(compression_error_maps({}, n, *b.compressed, errors, abs_error, 64), Error);
  EXPECT_THROW(compression_error_maps(exact, n, *b.compressed, errors, {}, 64), Error);
  EXPECT_THROW(compression_error_maps(exact, n + 1, *b.compressed, errors, abs_error, 64), Error);
}

}  // namespace
}  // namespace bounce
