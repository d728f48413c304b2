// A later kept pass encodes only the blocks whose kept entries changed. The
// blocks it stores must be those a full encoding of its texels gives: the
// test builds the texels on its own from the pass's kept entries, quantisers
// and importance, encodes the whole image, and compares byte for byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include <glm/glm.hpp>

#include "compress/block_image.h"
#include "compress/changed_blocks.h"
#include "compress/codec.h"
#include "compress/entry_importance.h"
#include "transport_like.h"

namespace bounce {

namespace {

struct Matrices {
  std::size_t n = 130;  // not a multiple of 4: the last block row and column are padded
  std::vector<std::vector<float>> t;
  std::vector<const float*> in;
  EntryImportance importance;

  Matrices() {
    t = {transport_like(n, 1.0f, 11), transport_like(n, 0.8f, 11), transport_like(n, 0.6f, 11)};
    for (const auto& m : t) in.push_back(m.data());
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<std::vector<glm::vec3>> lights(2, std::vector<glm::vec3>(n));
    for (auto& l : lights)
      for (auto& v : l) v = glm::vec3(u(rng), u(rng), u(rng));
    std::vector<float> area(n);
    for (float& a : area) a = 0.5f + u(rng);
    importance = light_importance(in, n, lights, {0, 1, 2}, area);
  }
};

bool is_kept(const CsrMatrix& k, std::size_t i, std::size_t j) {
  for (std::uint32_t e = k.row_ptr[i]; e < k.row_ptr[i + 1]; ++e)
    if (k.col[e] == j) return true;
  return false;
}

// The permuted, padded image of codes and weights of `m`, from its kept
// entries, quantisers and the importance alone.
void image_of(const Matrices& x, const CompressedMatrix& m, std::vector<std::uint8_t>& codes,
              std::vector<float>& weights) {
  const std::size_t n = x.n, w = m.padded;
  codes.assign(w * w * 3, 0);
  weights.assign(w * w * 3, 0.0f);
  for (std::size_t r = 0; r < n; ++r)
    for (std::size_t s = 0; s < n; ++s)
      for (std::size_t c = 0; c < 3; ++c) {
        const std::size_t i = m.permutation[r], j = m.permutation[s];
        if (is_kept(m.kept[c], i, j)) continue;
        const LogQuantizer& q = m.quantizers[c];
        const std::uint8_t code = q.encode(x.t[c][i * n + j]);
        codes[(r * w + s) * 3 + c] = code;
        weights[(r * w + s) * 3 + c] = q.weight(code) * x.importance.weight(c, i, j);
      }
}

CompressedMatrix light_weighted(const Matrices& x, int kept_passes) {
  CodecSettings s;
  s.kept_fraction = 0.03;
  s.importance = &x.importance;
  s.kept_passes = kept_passes;
  return compress_matrix(x.in, x.n, s);
}

}  // namespace

TEST(ChangedBlocks, ASecondKeptPassStoresWhatAFullEncodingOfItsTexelsGives) {
  const Matrices x;
  const CompressedMatrix m = light_weighted(x, 2);
  const std::size_t blocks = m.blocks.size() / 8;
  // The second pass encoded some blocks again, not all.
  EXPECT_GT(m.blocks_encoded, blocks);
  EXPECT_LT(m.blocks_encoded, 2 * blocks);
  std::vector<std::uint8_t> codes;
  std::vector<float> weights;
  image_of(x, m, codes, weights);
  const std::vector<std::uint8_t> full =
      encode_bc1_image(m.padded, m.padded, codes, weights, Bc1Encoder::kWeighted);
  EXPECT_EQ(full, m.blocks);
}

TEST(ChangedBlocks, MarksTheBlocksOfEntriesKeptByOnlyOneOfTwoCompressions) {
  CompressedMatrix a, b;
  a.n = b.n = 6;
  a.padded = b.padded = 8;
  a.permutation = b.permutation = {5, 4, 3, 2, 1, 0};  // patch i is stored at 5 - i
  a.blocks.assign(4 * 8, 0);
  b.blocks = a.blocks;
  const auto csr = [](std::vector<std::vector<std::uint32_t>> rows) {
    CsrMatrix k;
    k.n = rows.size();
    k.row_ptr.push_back(0);
    for (const auto& r : rows) {
      k.col.insert(k.col.end(), r.begin(), r.end());
      k.value.resize(k.col.size(), 1.0f);
      k.row_ptr.push_back(static_cast<std::uint32_t>(k.col.size()));
    }
    return k;
  };
  // Channel 0 the same in both; channel 1: (0, 1) only in a, (5, 5) only in b.
  a.kept = {csr({{2}, {}, {}, {}, {}, {}}), csr({{1, 3}, {}, {}, {}, {}, {}})};
  b.kept = {csr({{2}, {}, {}, {}, {}, {}}), csr({{3}, {}, {}, {}, {}, {5}})};
  // (0, 1) is stored at (5, 4): block (1, 1) = 3. (5, 5) at (0, 0): block 0.
  EXPECT_EQ(blocks_with_changed_holes(a, b), (std::vector<std::size_t>{0, 3}));
  EXPECT_TRUE(blocks_with_changed_holes(a, a).empty());
}

TEST(ChangedBlocks, EncodesOnlyTheBlocksItIsGiven) {
  const Matrices x;
  CompressedMatrix m = light_weighted(x, 1);
  const std::vector<std::uint8_t> encoded = m.blocks;
  std::vector<std::uint8_t> codes;
  std::vector<float> weights;
  // Texels in patch order, as the codec splits them.
  image_of(x, m, codes, weights);
  std::vector<std::uint8_t> patch_codes(x.n * x.n * 3);
  std::vector<float> patch_weights(patch_codes.size());
  for (std::size_t r = 0; r < x.n; ++r)
    for (std::size_t q = 0; q < x.n; ++q)
      for (std::size_t c = 0; c < 3; ++c) {
        const std::size_t to = (m.permutation[r] * x.n + m.permutation[q]) * 3 + c;
        patch_codes[to] = codes[(r * m.padded + q) * 3 + c];
        patch_weights[to] = weights[(r * m.padded + q) * 3 + c];
      }
  std::fill(m.blocks.begin(), m.blocks.end(), std::uint8_t{0xAB});
  const std::vector<std::size_t> which = {0, 7, m.blocks.size() / 8 - 1};
  BlockEncoding e;
  e.width = m.padded;
  encode_blocks_in_place(e, which, patch_codes, patch_weights, 3, m);
  for (std::size_t b = 0; b < m.blocks.size() / 8; ++b) {
    const bool given = b == which[0] || b == which[1] || b == which[2];
    for (std::size_t k = 0; k < 8; ++k)
      ASSERT_EQ(m.blocks[8 * b + k], given ? encoded[8 * b + k] : 0xAB) << "block " << b;
  }
}

}  // namespace bounce

namespace bounce {

// A sample holds its own rows' texels only: its blocks, both passes, are
// those block rows of a full encoding of the texels its kept entries and
// quantisers give.
TEST(ChangedBlocks, ASampledSecondPassStoresWhatAFullEncodingOfItsRowsGives) {
  const Matrices x;
  CodecSettings s;
  s.kept_fraction = 0.03;
  s.importance = &x.importance;
  s.kept_passes = 2;
  s.permutation = compress_matrix(x.in, x.n, s).permutation;
  s.block_rows = {1, 4, 5, 9, 15, 32};  // 33 block rows; the last is padded
  const CompressedMatrix m = compress_matrix(x.in, x.n, s);
  const std::size_t per_row = m.padded / 4;
  ASSERT_EQ(m.blocks.size(), s.block_rows.size() * per_row * 8);
  std::vector<std::uint8_t> codes;
  std::vector<float> weights;
  image_of(x, m, codes, weights);
  const std::vector<std::uint8_t> full =
      encode_bc1_image(m.padded, m.padded, codes, weights, Bc1Encoder::kWeighted);
  for (std::size_t k = 0; k < s.block_rows.size(); ++k)
    EXPECT_TRUE(
        std::equal(m.blocks.begin() + static_cast<std::ptrdiff_t>(k * per_row * 8),
                   m.blocks.begin() + static_cast<std::ptrdiff_t>((k + 1) * per_row * 8),
                   full.begin() + static_cast<std::ptrdiff_t>(s.block_rows[k] * per_row * 8)))
        << "block row " << s.block_rows[k];
}

}  // namespace bounce
