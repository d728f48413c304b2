// Why a patch's indirect light is wrong after compression: the sources of
// its row (blocks, kept entries) checked against the whole decoded matrix
// (decompress_channel), with block membership and kept positions worked out
// here from the permutation and the CSR arrays, term by term.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include <glm/glm.hpp>

#include "base/error.h"
#include "compress/codec.h"
#include "compress/row_error_contributions.h"
#include "transport_like.h"

namespace bounce {

namespace {

std::vector<glm::vec3> random_light(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<glm::vec3> b(n);
  // Mostly dark, a few bright patches: like a first hit.
  for (auto& x : b)
    x = u(rng) < 0.2f ? glm::vec3(u(rng), u(rng), u(rng)) * 5.0f : glm::vec3(0.01f * u(rng));
  return b;
}

bool is_kept(const CsrMatrix& kept, std::size_t row, std::size_t col) {
  for (std::uint32_t e = kept.row_ptr[row]; e < kept.row_ptr[row + 1]; ++e)
    if (kept.col[e] == col) return true;
  return false;
}

struct Case {
  const char* name;
  CodecKind kind;
  int channels;
  bool bc4_per_channel;
};

class RowErrorContributionsOf : public ::testing::TestWithParam<Case> {};

}  // namespace

TEST_P(RowErrorContributionsOf, SourcesAddUpToTheDecodedMatrixsErrorTermByTerm) {
  const Case v = GetParam();
  const std::size_t n = 45;  // not a multiple of 4: a padded last block
  std::vector<std::vector<float>> t;
  std::vector<const float*> exact;
  for (int c = 0; c < v.channels; ++c)
    t.push_back(transport_like(n, 1.0f - 0.2f * static_cast<float>(c), 3));
  for (const auto& x : t) exact.push_back(x.data());
  CodecSettings s;
  s.kind = v.kind;
  s.kept_fraction = 0.06;
  s.bc4_per_channel = v.bc4_per_channel;
  CompressedMatrix m = compress_matrix(exact, n, s);
  // A kept value that is not the exact one: its column's kept source must
  // carry exactly that entry's error, and no block may.
  CsrMatrix& k0 = m.kept[0];
  std::size_t tampered_row = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (k0.row_ptr[i + 1] - k0.row_ptr[i] > k0.row_ptr[tampered_row + 1] - k0.row_ptr[tampered_row])
      tampered_row = i;
  ASSERT_LT(k0.row_ptr[tampered_row], k0.row_ptr[tampered_row + 1]) << "the row keeps entries";
  const std::uint32_t tampered = k0.row_ptr[tampered_row];
  // The light-weighted codec keeps halves, the largest-entries one exact
  // floats: what was kept, before tampering.
  const double kept_before = k0.value[tampered];
  k0.value[tampered] *= 1.5f;

  const std::array<int, 3> channel_of_rgb =
      v.channels == 1 ? std::array<int, 3>{0, 0, 0} : std::array<int, 3>{0, 1, 2};
  std::vector<std::vector<float>> decoded(static_cast<std::size_t>(v.channels),
                                          std::vector<float>(n * n));
  for (int c = 0; c < v.channels; ++c)
    decompress_channel(m, c, decoded[static_cast<std::size_t>(c)].data());
  const std::vector<glm::vec3> b = random_light(n, 7);
  std::vector<std::size_t> inverse(n);
  for (std::size_t k = 0; k < n; ++k) inverse[m.permutation[k]] = k;

  for (const std::size_t p : {tampered_row, std::size_t{0}, n / 2, n - 1}) {
    SCOPED_TRACE("patch " + std::to_string(p));
    const RowErrorContributions r = row_error_contributions(m, exact, channel_of_rgb, b, p);
    EXPECT_EQ(r.patch, p);
    EXPECT_EQ(m.permutation[r.stored_row], p);
    // The row's light, exact and compressed, from the whole matrices.
    glm::dvec3 want_exact(0.0), want_compressed(0.0);
    for (std::size_t j = 0; j < n; ++j)
      for (int colour = 0; colour < 3; ++colour) {
        const auto c = static_cast<std::size_t>(channel_of_rgb[static_cast<std::size_t>(colour)]);
        want_exact[colour] += static_cast<double>(t[c][p * n + j]) * b[j][colour];
        want_compressed[colour] += static_cast<double>(decoded[c][p * n + j]) * b[j][colour];
      }
    const glm::dvec3 want_difference = want_compressed - want_exact;
    const double scale = glm::length(want_exact);
    ASSERT_GT(scale, 0.0);
    glm::dvec3 sum(0.0);
    double share_sum = 0.0;
    // Each (colour, column) term belongs to exactly one source.
    std::vector<std::array<int, 3>> counted(n, {0, 0, 0});
    for (const RowErrorSource& src : r.sources) {
      EXPECT_EQ(src.block_row, inverse[p] / 4);
      glm::dvec3 want(0.0);
      for (const RowEntry& e : src.entries) {
        EXPECT_EQ(m.permutation[e.stored_col], e.column);
        EXPECT_EQ(e.stored_col / 4, src.block_col);
        for (int colour = 0; colour < 3; ++colour) {
          const auto c = static_cast<std::size_t>(channel_of_rgb[static_cast<std::size_t>(colour)]);
          const bool kept = is_kept(m.kept[c], p, e.column);
          if (kept != (src.kind == RowErrorSource::Kind::Kept)) continue;
          ++counted[e.column][static_cast<std::size_t>(colour)];
          EXPECT_EQ(e.exact[colour], static_cast<double>(t[c][p * n + e.column]));
          EXPECT_EQ(e.decoded[colour], static_cast<double>(decoded[c][p * n + e.column]));
          want[colour] += (static_cast<double>(decoded[c][p * n + e.column]) -
                           static_cast<double>(t[c][p * n + e.column])) *
                          b[e.column][colour];
        }
      }
      for (int colour = 0; colour < 3; ++colour)
        EXPECT_NEAR(src.contribution[colour], want[colour], 1e-12 * scale);
      sum += src.contribution;
      share_sum += src.share;
    }
    // Terms of columns no source lists are zero: exact and decoded both 0.
    for (std::size_t j = 0; j < n; ++j)
      for (int colour = 0; colour < 3; ++colour) {
        const auto c = static_cast<std::size_t>(channel_of_rgb[static_cast<std::size_t>(colour)]);
        if (counted[j][static_cast<std::size_t>(colour)] == 0) {
          EXPECT_EQ(t[c][p * n + j], 0.0f) << "column " << j;
          EXPECT_EQ(decoded[c][p * n + j], 0.0f) << "column " << j;
        } else {
          EXPECT_EQ(counted[j][static_cast<std::size_t>(colour)], 1) << "column " << j;
        }
      }
    for (int colour = 0; colour < 3; ++colour) {
      EXPECT_NEAR(r.exact[colour], want_exact[colour], 1e-12 * scale);
      EXPECT_NEAR(r.compressed[colour], want_compressed[colour], 1e-12 * scale);
      EXPECT_NEAR(r.difference[colour], want_difference[colour], 1e-12 * scale);
      EXPECT_NEAR(sum[colour], want_difference[colour], 1e-12 * scale);
    }
    ASSERT_GT(glm::length(want_difference), 0.0) << "a lossy codec leaves an error";
    EXPECT_NEAR(share_sum, 1.0, 1e-9);
    for (std::size_t k = 1; k < r.sources.size(); ++k)
      EXPECT_GE(r.sources[k - 1].share, r.sources[k].share);
    if (p == tampered_row) {
      // The tampered entry's kept source: (1.5 kept - T_pj) b_j in the colours
      // of channel 0 (0.5 T_pj b_j when the kept value was exact).
      const std::size_t j = k0.col[tampered];
      const auto it = std::find_if(r.sources.begin(), r.sources.end(), [&](const auto& src) {
        return src.kind == RowErrorSource::Kind::Kept && src.entries[0].column == j;
      });
      ASSERT_NE(it, r.sources.end());
      for (int colour = 0; colour < 3; ++colour) {
        if (channel_of_rgb[static_cast<std::size_t>(colour)] == 0) {
          EXPECT_NEAR(it->contribution[colour],
                      (static_cast<double>(1.5f * static_cast<float>(kept_before)) -
                       static_cast<double>(t[0][p * n + j])) *
                          b[j][colour],
                      1e-6 * scale);
        }
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    Codecs, RowErrorContributionsOf,
    ::testing::Values(Case{"LightWeightedRgbBc1", CodecKind::LightWeighted, 3, false},
                      Case{"LightWeightedGreyBc4", CodecKind::LightWeighted, 1, false},
                      Case{"LightWeightedRgbBc4PerChannel", CodecKind::LightWeighted, 3, true},
                      Case{"LargestEntriesGreyBc1", CodecKind::LargestEntries, 1, false}),
    [](const ::testing::TestParamInfo<Case>& c) { return std::string(c.param.name); });

TEST(RowErrorContributions, WrongPatchOrLightIsAnError) {
  const std::size_t n = 12;
  const std::vector<float> t = transport_like(n, 1.0f, 1);
  const CompressedMatrix m = compress_matrix({t.data()}, n, CodecSettings{});
  const std::vector<glm::vec3> b(n, glm::vec3(1.0f));
  EXPECT_THROW(row_error_contributions(m, {t.data()}, {0, 0, 0}, b, n), Error);
  EXPECT_THROW(row_error_contributions(m, {t.data()}, {0, 0, 0}, {glm::vec3(1.0f)}, 0), Error);
  EXPECT_THROW(row_error_contributions(m, {t.data(), t.data()}, {0, 0, 0}, b, 0), Error);
  EXPECT_THROW(row_error_contributions(m, {t.data()}, {0, 1, 0}, b, 0), Error);
}

}  // namespace bounce
