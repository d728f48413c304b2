// compress_matrix's block encoding by ranges of block rows (what a
// distributed bake's ranks each do, core/distributed/mpi_compression.cpp)
// gives the bytes of the encoding in one piece, in every format: BC1 (ours
// and the paper's libsquish encoder), BC4, BC4 per channel.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "base/error.h"
#include "compress/codec.h"

namespace bounce {

namespace {

// Encodes the image in `parts` uneven ranges of block rows, the last range
// first, each from a copy of its rows only, as a rank receives them.
class RangesExecutor : public CompressionExecutor {
 public:
  explicit RangesExecutor(std::size_t parts) : parts_(parts) {}
  std::vector<std::uint8_t> encode_blocks(const BlockEncoding& e,
                                          std::span<const std::uint8_t> codes,
                                          std::span<const float> weights) override {
    const std::size_t rows = e.block_rows(), per_row = 4 * e.width * e.texel_channels();
    std::vector<std::uint8_t> blocks(e.images() * rows * e.block_row_bytes());
    for (std::size_t k = parts_; k-- > 0;) {
      // Ranges of unequal length: k^2 weighting, some of them empty.
      const std::size_t first = rows * k * k / (parts_ * parts_);
      const std::size_t end = rows * (k + 1) * (k + 1) / (parts_ * parts_);
      const std::vector<std::uint8_t> own_codes(codes.begin() + first * per_row,
                                                codes.begin() + end * per_row);
      const std::vector<float> own_weights(weights.begin() + first * per_row,
                                           weights.begin() + end * per_row);
      place_block_rows(e, first, end - first,
                       encode_block_rows(e, end - first, own_codes, own_weights), blocks);
      ++calls_;
    }
    return blocks;
  }
  std::string description() const override { return "ranges"; }
  int calls() const { return calls_; }

 private:
  std::size_t parts_;
  int calls_ = 0;
};

std::vector<float> smooth_matrix(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.5f, 1.0f);
  std::vector<float> t(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      t[i * n + j] = 0.02f *
                     std::exp(-std::abs(static_cast<float>(i) - static_cast<float>(j)) / 9.0f) *
                     u(rng);
  return t;
}

void expect_same_encoding(const std::vector<const float*>& matrices, std::size_t n,
                          const CodecSettings& settings, const char* what) {
  const CompressedMatrix whole = compress_matrix(matrices, n, settings);
  RangesExecutor ranges(5);
  const CompressedMatrix parts = compress_matrix(matrices, n, settings, nullptr, &ranges);
  EXPECT_EQ(ranges.calls(), 5) << what;
  ASSERT_FALSE(whole.blocks.empty()) << what;
  EXPECT_TRUE(whole.blocks == parts.blocks) << what;
  EXPECT_EQ(whole.permutation, parts.permutation) << what;
  EXPECT_EQ(whole.encoder, parts.encoder) << what;
}

}  // namespace

TEST(BlockRows, EncodingByRangesOfBlockRowsEqualsTheWholeImageInEveryFormat) {
  const std::size_t n = 61;  // padded to 64: 16 block rows, the last with padding
  const std::vector<float> r = smooth_matrix(n, 1), g = smooth_matrix(n, 2),
                           b = smooth_matrix(n, 3);
  const std::vector<const float*> colour = {r.data(), g.data(), b.data()}, grey = {r.data()};
  CodecSettings ours;
  expect_same_encoding(colour, n, ours, "ours, BC1");
  expect_same_encoding(grey, n, ours, "ours, BC4");
  CodecSettings paper;
  paper.kind = CodecKind::LargestEntries;
  expect_same_encoding(colour, n, paper, "paper, BC1 by libsquish");
  CodecSettings planar;
  planar.bc4_per_channel = true;
  expect_same_encoding(colour, n, planar, "BC4 per channel");
}

TEST(BlockRows, RowsThatDoNotFitTheImageAreRefused) {
  BlockEncoding e;
  e.width = 16;  // 4 block rows of 4 blocks
  std::vector<std::uint8_t> blocks(4 * e.block_row_bytes());
  const std::vector<std::uint8_t> two_rows(2 * e.block_row_bytes());
  EXPECT_NO_THROW(place_block_rows(e, 2, 2, two_rows, blocks));
  EXPECT_THROW(place_block_rows(e, 3, 2, two_rows, blocks), Error);  // past the last row
  EXPECT_THROW(place_block_rows(e, 0, 1, two_rows, blocks), Error);  // wrong size
}

}  // namespace bounce
