// The compression pipeline end to end on a matrix shaped like a transport
// matrix: kept entries exact (paper) or within half precision (ours), the
// permutation undone exactly, errors computed
// here independently, and ours against the published pipeline.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include <glm/glm.hpp>

#include "base/error.h"
#include "compress/codec.h"
#include "compress/matrix_error.h"
#include "transport_like.h"

namespace bounce {

namespace {

MatrixError errors(const CompressedMatrix& m, const std::vector<std::vector<float>>& exact) {
  MatrixErrorAccumulator acc;
  std::vector<float> out(m.n * m.n);
  for (int c = 0; c < m.channels; ++c) {
    decompress_channel(m, c, out.data());
    acc.add(exact[static_cast<std::size_t>(c)].data(), out.data(), out.size());
  }
  return acc.result();
}

// Whether a kept entry decodes to its value: exactly in float32; in float16
// rounded to the nearest of 11 significant bits: off by at most half a step
// of 2^-10 of the value's power of two, so by at most 2^-11 of itself, or by
// half the smallest subnormal step (2^-25) below the normals.
bool kept_matches(float decoded, float exact, KeptStorage storage) {
  if (storage == KeptStorage::kFloat32) return decoded == exact;
  const double off = std::abs(static_cast<double>(decoded) - static_cast<double>(exact));
  return off <=
         std::max(std::ldexp(std::abs(static_cast<double>(exact)), -11), std::ldexp(1.0, -25));
}

}  // namespace

TEST(Codec, KeptEntriesAreHalvesOfTheirValuesAndEveryEntryDecodesNearIt) {
  const std::size_t n = 101;  // not a multiple of 4: padding
  const std::vector<float> t = transport_like(n, 1.0f, 1);
  CodecSettings s;
  const CompressedMatrix m = compress_matrix({t.data()}, n, s);
  EXPECT_EQ(m.padded, 104u);
  EXPECT_TRUE(is_bijection(m.permutation));
  std::vector<float> out(n * n);
  decompress_channel(m, 0, out.data());
  const CsrMatrix& kept = m.kept[0];
  EXPECT_NEAR(static_cast<double>(kept.value.size()), 0.04 * n * n, 1.0);
  ASSERT_EQ(m.kept_storage, KeptStorage::kFloat16);
  int rounded = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t k = kept.row_ptr[i]; k < kept.row_ptr[i + 1]; ++k) {
      const float exact = t[i * n + kept.col[k]];
      EXPECT_TRUE(kept_matches(out[i * n + kept.col[k]], exact, m.kept_storage)) << exact;
      rounded += out[i * n + kept.col[k]] != exact;
    }
  // Float values of a real matrix are almost never halves: the rounding took place.
  EXPECT_GT(rounded, static_cast<int>(kept.value.size()) / 2);
  // 4 bytes an entry (uint16 column, half value) and the row starts.
  EXPECT_EQ(m.sparse_bytes(), (n + 1) * 4 + kept.value.size() * 4);
  // Nothing decodes above the largest dense value (a kept half up to 2^-11
  // above its value) nor below zero.
  for (std::size_t k = 0; k < n * n; ++k) {
    EXPECT_GE(out[k], 0.0f);
    EXPECT_LE(out[k], std::max(t[k] * (1.0f + 0x1p-11f), m.quantizers[0].vmax * 1.0001f));
  }
}

// Every codec variant, round trip: the kept entries come back as stored, the
// rest within the block format's error (checked as an upper bound: decoded
// values stay in [0, max(value, vmax)]), and a real permutation.
struct Variant {
  const char* name;
  CodecKind kind;
  int channels;
  bool bc4_per_channel;
};

class CodecRoundTrip : public ::testing::TestWithParam<Variant> {};

TEST_P(CodecRoundTrip, KeptExactRestBoundedPermutationBijective) {
  const Variant v = GetParam();
  const std::size_t n = 77;
  std::vector<std::vector<float>> t;
  std::vector<const float*> in;
  // Channels of one scene: the same geometry, different albedo scales.
  for (int c = 0; c < v.channels; ++c)
    t.push_back(transport_like(n, 1.0f - 0.1f * static_cast<float>(c), 5));
  for (const auto& x : t) in.push_back(x.data());
  CodecSettings s;
  s.kind = v.kind;
  s.bc4_per_channel = v.bc4_per_channel;
  const CompressedMatrix m = compress_matrix(in, n, s);
  EXPECT_TRUE(is_bijection(m.permutation));
  EXPECT_EQ(m.kept_storage,
            v.kind == CodecKind::LargestEntries ? KeptStorage::kFloat32 : KeptStorage::kFloat16);
  EXPECT_EQ(m.block_bytes(), (v.bc4_per_channel ? v.channels : 1) * 20u * 20u * 8u);
  std::vector<float> out(n * n);
  for (int c = 0; c < v.channels; ++c) {
    decompress_channel(m, c, out.data());
    const auto& exact = t[static_cast<std::size_t>(c)];
    const CsrMatrix& kept = m.kept[static_cast<std::size_t>(c)];
    for (std::size_t i = 0; i < n; ++i)
      for (std::uint32_t k = kept.row_ptr[i]; k < kept.row_ptr[i + 1]; ++k)
        ASSERT_TRUE(
            kept_matches(out[i * n + kept.col[k]], exact[i * n + kept.col[k]], m.kept_storage));
    const float vmax = m.quantizers[static_cast<std::size_t>(c)].vmax;
    for (std::size_t k = 0; k < n * n; ++k) {
      ASSERT_GE(out[k], 0.0f);
      ASSERT_LE(out[k], std::max(exact[k] * (1.0f + 0x1p-11f), vmax * 1.0001f));
    }
  }
  // The error is that of a lossy codec, not of a broken one: well under the
  // matrix itself (a decode of the wrong channel or order gives ~100%).
  EXPECT_LT(errors(m, t).rel_frobenius, 0.3);
}

INSTANTIATE_TEST_SUITE_P(
    Variants, CodecRoundTrip,
    ::testing::Values(Variant{"paper_rgb", CodecKind::LargestEntries, 3, false},
                      Variant{"paper_grey", CodecKind::LargestEntries, 1, false},
                      Variant{"ours_rgb", CodecKind::LightWeighted, 3, false},
                      Variant{"ours_grey", CodecKind::LightWeighted, 1, false},
                      Variant{"ours_bc4_per_channel", CodecKind::LightWeighted, 3, true}),
    [](const ::testing::TestParamInfo<Variant>& p) { return p.param.name; });

TEST(Codec, GreySceneIsOneBc4ChannelColourIsBc1) {
  const std::size_t n = 64;
  const std::vector<float> t = transport_like(n, 1.0f, 2);
  EXPECT_EQ(compress_matrix({t.data()}, n, {}).format, DdsFormat::kBc4);
  EXPECT_EQ(compress_matrix({t.data(), t.data(), t.data()}, n, {}).format, DdsFormat::kBc1);
  CodecSettings paper;
  paper.kind = CodecKind::LargestEntries;
  EXPECT_EQ(compress_matrix({t.data()}, n, paper).format, DdsFormat::kBc1);
}

TEST(Codec, LightWeightedBeatsThePublishedPipelineAtTheSameSize) {
  const std::size_t n = 256;
  const std::vector<std::vector<float>> t = {transport_like(n, 1.0f, 3), transport_like(n, 0.9f, 3),
                                             transport_like(n, 0.8f, 3)};
  const std::vector<const float*> in = {t[0].data(), t[1].data(), t[2].data()};
  CodecSettings paper;
  paper.kind = CodecKind::LargestEntries;
  const CompressedMatrix mp = compress_matrix(in, n, paper);
  // Ours at the same bytes: half-precision kept entries take 4 bytes where
  // the paper's take 8, so twice as many fit.
  CodecSettings ours;
  ours.kept_fraction = 2.0 * paper.kept_fraction;
  const CompressedMatrix mo = compress_matrix(in, n, ours);
  // The same bytes up to the rounding of each channel's kept count (an entry
  // or two each side).
  EXPECT_NEAR(static_cast<double>(mo.total_bytes()), static_cast<double>(mp.total_bytes()),
              3 * 2 * 4);
  const MatrixError ep = errors(mp, t), eo = errors(mo, t);
  std::printf("sum |error|: paper %.4g, ours %.4g (ratio %.3f); rel Frobenius %.4g vs %.4g\n",
              ep.sum_abs, eo.sum_abs, eo.sum_abs / ep.sum_abs, ep.rel_frobenius, eo.rel_frobenius);
  // The codec's target is half the paper's sum |error| at no larger size; on
  // this matrix ours measures 0.26x (0.42x with float32 kept entries; the
  // fitted log range alone takes it from 0.61x).
  EXPECT_LT(eo.sum_abs, 0.5 * ep.sum_abs);
  EXPECT_LT(eo.rel_frobenius, 0.5 * ep.rel_frobenius);
}

TEST(Codec, PrecomputedPermutationGivesTheSameResultWithoutOrdering) {
  // bounce bench compress computes each ordering once and hands it to the
  // other encoders: the result must be the one a full run gives.
  const std::size_t n = 96;
  const std::vector<float> t0 = transport_like(n, 1.0f, 4), t1 = transport_like(n, 0.9f, 4),
                           t2 = transport_like(n, 0.8f, 4);
  const std::vector<const float*> in = {t0.data(), t1.data(), t2.data()};
  CodecSettings s;
  s.ordering = OrderingMethod::GreedyRowThenColumnTour;
  s.bc1_encoder = Bc1Encoder::kStbHighQuality;
  const CompressedMatrix full = compress_matrix(in, n, s);
  s.permutation = full.permutation;
  const CompressedMatrix reused = compress_matrix(in, n, s);
  EXPECT_EQ(reused.permutation, full.permutation);
  EXPECT_EQ(reused.blocks, full.blocks);
  EXPECT_EQ(reused.ordering, full.ordering);
  EXPECT_EQ(reused.seconds_ordering, 0.0);

  s.permutation = Permutation(n, 0);  // not a bijection
  EXPECT_THROW(compress_matrix(in, n, s), Error);
  s.permutation = identity_permutation(n - 1);  // wrong size
  EXPECT_THROW(compress_matrix(in, n, s), Error);
}

}  // namespace bounce
