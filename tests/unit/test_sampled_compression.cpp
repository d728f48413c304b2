// Compression of a sample of block rows, as the error budget's search runs
// it: with every block row it is the whole compression bit for bit, a sample
// keeps the same share of its own entries, and its light error is the one
// computed here independently on the sampled rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/glm.hpp>

#include "bake/matrix_storage.h"
#include "base/error.h"
#include "compress/codec.h"
#include "compress/compression_error.h"
#include "compress/entry_importance.h"
#include "compress/sparse_split.h"
#include "transport_like.h"

namespace bounce {

namespace {

struct Fixture {
  std::size_t n = 130;  // not a multiple of 4: the last block row is padded
  std::vector<std::vector<float>> t;
  std::vector<const float*> in;
  IndirectLightProbe probe;
  EntryImportance importance;

  Fixture() {
    t = {transport_like(n, 1.0f, 7), transport_like(n, 0.9f, 7), transport_like(n, 0.7f, 7)};
    for (const auto& m : t) in.push_back(m.data());
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int l = 0; l < 3; ++l) {
      std::vector<glm::vec3> b(n);
      for (auto& v : b) v = glm::vec3(u(rng), u(rng), u(rng));
      probe.first_hit.push_back(b);
    }
    probe.area.assign(n, 1.0f);
    for (std::size_t i = 0; i < n; ++i) probe.area[i] = 0.5f + u(rng);
    importance = light_importance(in, n, probe.first_hit, probe.channel_of_rgb, probe.area);
  }

  CodecSettings ours(double kept_fraction) const {
    CodecSettings s;
    s.kept_fraction = kept_fraction;
    s.importance = &importance;
    return s;
  }
};

std::vector<std::uint32_t> every_block_row(std::size_t n) {
  std::vector<std::uint32_t> rows((n + 3) / 4);
  for (std::size_t b = 0; b < rows.size(); ++b) rows[b] = static_cast<std::uint32_t>(b);
  return rows;
}

}  // namespace

TEST(SampledCompression, EveryBlockRowIsTheWholeCompression) {
  const Fixture f;
  CodecSettings s = f.ours(0.03);
  const CompressedMatrix whole = compress_matrix(f.in, f.n, s);
  s.permutation = whole.permutation;
  s.block_rows = every_block_row(f.n);
  const CompressedMatrix sample = compress_matrix(f.in, f.n, s);
  ASSERT_TRUE(sample.sampled());
  EXPECT_EQ(sample.blocks, whole.blocks);
  for (int c = 0; c < 3; ++c) {
    const auto k = static_cast<std::size_t>(c);
    EXPECT_EQ(sample.kept[k].col, whole.kept[k].col);
    EXPECT_EQ(sample.kept[k].value, whole.kept[k].value);
    EXPECT_EQ(sample.quantizers[k].vmax, whole.quantizers[k].vmax);
    EXPECT_EQ(sample.quantizers[k].range, whole.quantizers[k].range);
  }
  const CompressionErrors a = measure_compression(f.in, whole, f.probe);
  const CompressionErrors b = measure_compression(f.in, sample, f.probe);
  EXPECT_EQ(a.indirect.per_light, b.indirect.per_light);
  EXPECT_EQ(a.matrix.rel_frobenius, b.matrix.rel_frobenius);
}

TEST(SampledCompression, KeepsTheSameShareOfItsOwnRowsOnly) {
  const Fixture f;
  CodecSettings s = f.ours(0.05);
  s.kept_passes = 1;
  s.permutation = compress_matrix(f.in, f.n, s).permutation;
  s.block_rows = {1, 5, 9, 20};
  const CompressedMatrix m = compress_matrix(f.in, f.n, s);
  const std::vector<std::uint32_t> rows = m.rows();
  ASSERT_EQ(rows.size(), 16u);
  EXPECT_TRUE(std::is_sorted(rows.begin(), rows.end()));
  EXPECT_EQ(m.blocks.size(), s.block_rows.size() * (m.padded / 4) * 8);
  for (const CsrMatrix& kept : m.kept) {
    std::size_t in_rows = 0;
    for (std::size_t i = 0; i < f.n; ++i) {
      const std::size_t count = kept.row_ptr[i + 1] - kept.row_ptr[i];
      if (std::binary_search(rows.begin(), rows.end(), static_cast<std::uint32_t>(i)))
        in_rows += count;
      else
        EXPECT_EQ(count, 0u) << "row " << i << " is not in the sample";
    }
    // 5% of 16 x 130 entries (ties at the threshold could add a few).
    EXPECT_GE(in_rows, 104u);
    EXPECT_LE(in_rows, 106u);
  }
}

TEST(SampledCompression, LightErrorIsTheSampledRowsOwn) {
  const Fixture f;
  CodecSettings s = f.ours(0.02);
  s.permutation = compress_matrix(f.in, f.n, s).permutation;
  s.block_rows = {0, 3, 4, 11, 32};  // 32: the padded last block row
  const CompressedMatrix m = compress_matrix(f.in, f.n, s);
  const std::vector<std::uint32_t> rows = m.rows();
  ASSERT_EQ(rows.size(), 4u * 4 + 2);
  std::vector<std::vector<float>> decoded(3, std::vector<float>(rows.size() * f.n));
  for (int c = 0; c < 3; ++c) decompress_channel(m, c, decoded[static_cast<std::size_t>(c)].data());
  const CompressionErrors e = measure_compression(f.in, m, f.probe);
  ASSERT_EQ(e.indirect.per_light.size(), f.probe.first_hit.size());
  for (std::size_t l = 0; l < f.probe.first_hit.size(); ++l) {
    double err2 = 0.0, ref2 = 0.0;
    for (std::size_t c = 0; c < 3; ++c)
      for (std::size_t k = 0; k < rows.size(); ++k) {
        double exact = 0.0, approx = 0.0;
        for (std::size_t j = 0; j < f.n; ++j) {
          const double b = f.probe.first_hit[l][j][static_cast<int>(c)];
          exact += f.t[c][rows[k] * f.n + j] * b;
          approx += decoded[c][k * f.n + j] * b;
        }
        err2 += f.probe.area[rows[k]] * (approx - exact) * (approx - exact);
        ref2 += f.probe.area[rows[k]] * exact * exact;
      }
    EXPECT_NEAR(e.indirect.per_light[l], std::sqrt(err2 / ref2), 1e-9);
    EXPECT_GT(e.indirect.per_light[l], 0.0);
  }
  std::vector<float> map;
  EXPECT_THROW(measure_compression(f.in, m, f.probe, &map), Error);
}

TEST(SampledCompression, RefusesASampleWithoutPermutationOrOutOfOrder) {
  const Fixture f;
  CodecSettings s = f.ours(0.02);
  s.block_rows = {0, 1};
  EXPECT_THROW(compress_matrix(f.in, f.n, s), Error);
  s.permutation = identity_permutation(f.n);
  s.block_rows = {2, 1};
  EXPECT_THROW(compress_matrix(f.in, f.n, s), Error);
  s.block_rows = {33};  // 130 patches: block rows 0..32
  EXPECT_THROW(compress_matrix(f.in, f.n, s), Error);
}

TEST(SampledCompression, SearchSampleStridesEveryKindOfRow) {
  for (std::size_t n : {5u, 130u, 600u, 4348u, 16384u}) {
    const std::vector<std::uint32_t> sample = search_sample_block_rows(n);
    const std::size_t block_rows = (n + 3) / 4;
    ASSERT_FALSE(sample.empty());
    EXPECT_TRUE(std::is_sorted(sample.begin(), sample.end()));
    EXPECT_LT(sample.back(), block_rows);
    // At least the minimum (or all), at most every stride-th.
    EXPECT_GE(sample.size(), std::min(block_rows, kSearchSampleMinBlockRows) * 9 / 10) << n;
    EXPECT_GE(sample.size() * kSearchSampleStride + kSearchSampleStride, block_rows) << n;
    if (block_rows <= kSearchSampleMinBlockRows) {
      EXPECT_EQ(sample.size(), block_rows);
    }
  }
}

TEST(SparseSplit, RowsVersionKeepsTheWholeMatrixsEntriesOnEveryRow) {
  const std::size_t n = 64;
  const std::vector<float> t = transport_like(n, 1.0f, 5);
  std::vector<std::uint32_t> all(n);
  for (std::size_t i = 0; i < n; ++i) all[i] = static_cast<std::uint32_t>(i);
  const float threshold = kept_threshold(t.data(), n, 0.04);
  EXPECT_EQ(kept_threshold(t.data(), n, all, 0.04), threshold);
  const CsrMatrix a = extract_kept(t.data(), n, threshold);
  const CsrMatrix b = extract_kept(t.data(), n, threshold, nullptr, all);
  EXPECT_EQ(a.row_ptr, b.row_ptr);
  EXPECT_EQ(a.col, b.col);
  EXPECT_EQ(a.value, b.value);
}

}  // namespace bounce
