// The run-time product indirect_k = T~_c(k) b_k from a compressed matrix, in
// C++ (both block loops) and on OpenCL, against the dense product of
// decompress_channel's output computed here in double: matrices from both
// codecs, three stored channels and one (BC1 and BC4), n not a multiple of 4,
// and blocks of random bytes, which reach every palette mode of BC1 and BC4
// that real encoders may avoid. Plus the OpenBLAS baseline and the embedded
// kernel sources. DISABLED_BenchRuntime times every path at N = 4096.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include <glm/glm.hpp>

#include "base/error.h"
#include "compress/block_bc1.h"
#include "compress/codec.h"
#include "compute/kernel_source.h"
#include "compute/opencl_context.h"
#include "runtime/compressed_transport.h"
#include "runtime/compressed_transport_cl.h"
#include "runtime/dense_transport.h"
#include "runtime_bench.h"

namespace bounce {

namespace {

constexpr std::size_t kN = 203;  // not a multiple of 4: a padding row and column of blocks

// Transport-like matrices: light exchange between random points on three
// walls of a box (smooth in space, unordered in index), one per stored
// channel, each with its own scale and a little noise of its own, so the
// channels' kept entries are mostly but not exactly the same positions.
std::vector<std::vector<float>> transport_like(std::size_t n, int channels, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<glm::vec3> p(n);
  for (glm::vec3& x : p) {
    const int wall = static_cast<int>(u(rng) * 3.0f);
    x = wall == 0   ? glm::vec3(u(rng), u(rng), 0.0f)
        : wall == 1 ? glm::vec3(0.0f, u(rng), u(rng))
                    : glm::vec3(u(rng), 0.0f, u(rng));
  }
  std::vector<std::vector<float>> t(static_cast<std::size_t>(channels), std::vector<float>(n * n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      const float base = i == j ? 0.0f : 0.01f * std::exp(-glm::length(p[i] - p[j]) / 0.15f);
      for (std::size_t c = 0; c < t.size(); ++c)
        t[c][i * n + j] = base * (1.0f - 0.1f * static_cast<float>(c)) * (1.0f + 0.1f * u(rng));
    }
  return t;
}

std::vector<const float*> pointers(const std::vector<std::vector<float>>& t) {
  std::vector<const float*> p;
  for (const auto& m : t) p.push_back(m.data());
  return p;
}

// Blocks of random bytes (both BC1 modes, both BC4 modes, every index), a
// random permutation and random kept entries above every decodable value.
CompressedMatrix random_blocks(std::size_t n, int channels, DdsFormat format, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  CompressedMatrix m;
  m.n = n;
  m.padded = (n + 3) / 4 * 4;
  m.channels = channels;
  m.format = format;
  m.permutation.resize(n);
  std::iota(m.permutation.begin(), m.permutation.end(), 0u);
  std::shuffle(m.permutation.begin(), m.permutation.end(), rng);
  for (int c = 0; c < channels; ++c) {
    LogQuantizer q;
    q.vmax = 0.01f * (1.0f + static_cast<float>(c));
    q.range = 8.0f;
    m.quantizers.push_back(q);
    CsrMatrix kept;
    kept.n = n;
    kept.row_ptr.push_back(0);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < n; ++j)
        if (u(rng) < 0.05f) {
          kept.col.push_back(static_cast<std::uint32_t>(j));
          kept.value.push_back(q.vmax * (1.0f + u(rng)));
        }
      kept.row_ptr.push_back(static_cast<std::uint32_t>(kept.col.size()));
    }
    m.kept.push_back(std::move(kept));
  }
  m.blocks.resize(m.padded / 4 * m.padded / 4 * 8);
  for (std::uint8_t& x : m.blocks) x = static_cast<std::uint8_t>(rng() & 0xFF);
  return m;
}

std::vector<glm::vec3> random_light(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<glm::vec3> b(n);
  for (glm::vec3& v : b) v = glm::vec3(u(rng), u(rng), u(rng));
  return b;
}

// The dense product of decompress_channel's matrices, in double, and per
// entry the sum of |T| |b| that float32 rounding errors are relative to.
struct Reference {
  std::vector<glm::dvec3> y, scale;
};

Reference dense_reference(const CompressedMatrix& m, const std::array<int, 3>& channel_of_rgb,
                          const std::vector<glm::vec3>& b) {
  const std::size_t n = m.n;
  std::vector<std::vector<float>> t(static_cast<std::size_t>(m.channels),
                                    std::vector<float>(n * n));
  for (int c = 0; c < m.channels; ++c)
    decompress_channel(m, c, t[static_cast<std::size_t>(c)].data());
  Reference r{std::vector<glm::dvec3>(n), std::vector<glm::dvec3>(n)};
  for (int k = 0; k < 3; ++k) {
    const std::vector<float>& tc = t[static_cast<std::size_t>(
        m.channels == 1 ? 0 : channel_of_rgb[static_cast<std::size_t>(k)])];
    for (std::size_t p = 0; p < n; ++p)
      for (std::size_t q = 0; q < n; ++q) {
        const double v = static_cast<double>(tc[p * n + q]) * static_cast<double>(b[q][k]);
        r.y[p][k] += v;
        r.scale[p][k] += std::abs(v);
      }
  }
  return r;
}

// Largest |y - reference| / sum |T| |b| over patches and colours.
double worst_error(const std::vector<glm::vec3>& y, const Reference& r) {
  double worst = 0.0;
  for (std::size_t p = 0; p < r.y.size(); ++p)
    for (int k = 0; k < 3; ++k) {
      const double e = std::abs(static_cast<double>(y[p][k]) - r.y[p][k]);
      worst = std::max(worst, r.scale[p][k] > 0.0 ? e / r.scale[p][k] : e);
    }
  return worst;
}

// Float32 sums of ~200 terms: 1e-7 to 1e-6 of sum |T| |b| measured, n eps ~
// 1.2e-5 at the very worst. A texel decoded one code off (a relative step of
// range / 255 in one of ~200 terms) is 1e-4 of a row or more; so is a wrong
// index width or palette slot, which the kernel mutations tried here showed.
constexpr double kTolerance = 1e-5;

struct Case {
  std::string name;
  CompressedMatrix m;
  std::array<int, 3> channel_of_rgb{0, 1, 2};
};

std::vector<Case> codec_cases() {
  const std::vector<std::vector<float>> colour = transport_like(kN, 3, 1);
  const std::vector<std::vector<float>> grey = transport_like(kN, 1, 2);
  CodecSettings paper, ours;
  paper.kind = CodecKind::LargestEntries;
  std::vector<Case> cases;
  cases.push_back({"paper, 3 channels (BC1)", compress_matrix(pointers(colour), kN, paper)});
  cases.push_back({"ours, 3 channels (BC1)", compress_matrix(pointers(colour), kN, ours)});
  cases.push_back({"ours, 3 channels, colours mapped B G R", cases.back().m, {2, 1, 0}});
  cases.push_back({"ours, 3 channels, colours mapped R R B", cases.back().m, {0, 0, 2}});
  cases.push_back({"paper, 1 channel (BC1, in R)", compress_matrix(pointers(grey), kN, paper)});
  cases.push_back({"ours, 1 channel (BC4)", compress_matrix(pointers(grey), kN, ours)});
  EXPECT_EQ(cases[0].m.format, DdsFormat::kBc1);
  EXPECT_EQ(cases[4].m.format, DdsFormat::kBc1);
  EXPECT_EQ(cases[5].m.format, DdsFormat::kBc4);
  cases.push_back({"random blocks, 3 channels (BC1)", random_blocks(kN, 3, DdsFormat::kBc1, 3)});
  cases.push_back({"random blocks, 1 channel (BC1)", random_blocks(kN, 1, DdsFormat::kBc1, 4)});
  cases.push_back({"random blocks, 1 channel (BC4)", random_blocks(kN, 1, DdsFormat::kBc4, 5)});
  return cases;
}

// Compressing takes most of these tests' time: once per test binary.
const std::vector<Case>& cases() {
  static const std::vector<Case> c = codec_cases();
  return c;
}

bool opencl_device(std::string& why) {
  try {
    OpenClContext::shared();
    return true;
  } catch (const Error& e) {
    why = e.what();
    return false;
  }
}

bool bitwise_equal(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec3)) == 0;
}

}  // namespace

TEST(CompressedTransport, MatchesTheDenseProductOfTheDecompressedMatrix) {
  const std::vector<glm::vec3> b = random_light(kN, 11);
  for (const Case& c : cases()) {
    const Reference r = dense_reference(c.m, c.channel_of_rgb, b);
    for (BlockLoop loop : {BlockLoop::kFloat32, BlockLoop::kAvx2, BlockLoop::kPortable}) {
      const CompressedTransport t(c.m, c.channel_of_rgb, loop);
      std::vector<glm::vec3> y;
      t.multiply(b, y);
      ASSERT_EQ(y.size(), kN);
      const double worst = worst_error(y, r);
      std::printf("%-40s %-8s loop: worst error / sum |T||b| = %.2e\n", c.name.c_str(),
                  t.block_loop(), worst);
      EXPECT_LE(worst, kTolerance) << c.name << ", " << t.block_loop() << " loop";
    }
  }
}

// The bfloat16 loop rounds each palette value and each b to 8-bit mantissas
// (relative error <= 2^-9 each), so each product is off by at most
// (2 * 2^-9 + 2^-18) |T||b| and a row by ~2^-8 of sum |T||b|, plus the
// float32 sums above. A wrong index, palette or block grouping (the loop
// reads groups of 8 neighbouring blocks; kN gives 51 block columns: 6 full
// groups and one of 3 blocks and 5 padding blocks) is off by far more, as
// the float32 loops' tolerance argument says. BlockLoop::kFastest, the
// default, is the bfloat16 loop where the CPU has it.
TEST(CompressedTransport, Bf16LoopIsWithinItsRoundingBound) {
  if (!CompressedTransport::has_bf16_loop()) GTEST_SKIP() << "no AVX-512 BF16 + VBMI on this CPU";
  const double bound = std::ldexp(1.0, -8) + std::ldexp(1.0, -18) + kTolerance;
  const std::vector<glm::vec3> b = random_light(kN, 13);
  for (const Case& c : cases()) {
    const Reference r = dense_reference(c.m, c.channel_of_rgb, b);
    const CompressedTransport t(c.m, c.channel_of_rgb, BlockLoop::kFastest);
    if (c.m.format != DdsFormat::kBc1) {
      EXPECT_STRNE(t.block_loop(), "avx512-bf16") << c.name << ": BC4 has no bfloat16 loop";
      continue;
    }
    ASSERT_STREQ(t.block_loop(), "avx512-bf16") << c.name;
    std::vector<glm::vec3> y;
    t.multiply(b, y);
    const double worst = worst_error(y, r);
    std::printf("%-40s bf16 loop: worst error / sum |T||b| = %.2e (bound %.2e)\n", c.name.c_str(),
                worst, bound);
    EXPECT_LE(worst, bound) << c.name;
    // Zero light still gives exactly zero.
    t.multiply(std::vector<glm::vec3>(kN, glm::vec3(0.0f)), y);
    for (const glm::vec3& v : y) ASSERT_TRUE(v == glm::vec3(0.0f)) << c.name;
  }
}

// The AVX-512 loops run bands of 8 block rows over tiles of 1024 stored
// columns of b (128 block pairs in float32, 32 groups of 8 blocks in
// bfloat16), reading the blocks in that order (runtime/block_loops.h).
// kN fits one tile and a short last band; at n = 2049 (513 block rows and
// columns) a row spans three tiles, the last holding only the odd last
// block (float32: one pair, bfloat16: one group with 7 padding blocks), and
// the last band has one block row. A record laid out in the wrong
// place, a tile's b or a band's row mixed up, is a wrong block: off by far
// more than either tolerance, as above.
TEST(CompressedTransport, SeveralTilesAndBandsMatchTheDenseProduct) {
  constexpr std::size_t n = 2049;
  const CompressedMatrix m = random_blocks(n, 3, DdsFormat::kBc1, 31);
  const std::vector<glm::vec3> b = random_light(n, 32);
  const Reference r = dense_reference(m, {0, 1, 2}, b);
  const double bf16_bound = std::ldexp(1.0, -8) + std::ldexp(1.0, -18) + kTolerance;
  for (BlockLoop loop : {BlockLoop::kFloat32, BlockLoop::kFastest, BlockLoop::kAvx2}) {
    const CompressedTransport t(m, {0, 1, 2}, loop);
    std::vector<glm::vec3> y;
    t.multiply(b, y);
    const double worst = worst_error(y, r);
    const bool bf16 = std::string(t.block_loop()) == "avx512-bf16";
    std::printf("n = %zu, %-12s loop: worst error / sum |T||b| = %.2e\n", n, t.block_loop(), worst);
    EXPECT_LE(worst, bf16 ? bf16_bound : kTolerance) << t.block_loop() << " loop";
  }
}

// Round to nearest even against the definition: the nearer of the two
// bfloat16 neighbours (truncation and the next one up), the even one on a tie.
TEST(Bfloat16, RoundsToNearestEven) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<std::uint32_t> bits(0, 0xFFFFFFFFu);
  for (int i = 0; i < 200000; ++i) {
    float x = std::bit_cast<float>(bits(rng));
    if (!std::isfinite(x) || std::abs(x) > 3.3e38f) continue;
    const std::uint32_t u = std::bit_cast<std::uint32_t>(x);
    const auto down = static_cast<std::uint16_t>(u >> 16);
    const auto up = static_cast<std::uint16_t>(down + 1);
    const double dd = std::abs(static_cast<double>(from_bfloat16(down)) - x);
    const double du = std::abs(static_cast<double>(from_bfloat16(up)) - x);
    const std::uint16_t expected = dd < du ? down : du < dd ? up : (down % 2 == 0 ? down : up);
    ASSERT_EQ(to_bfloat16(x), expected) << x;
  }
  EXPECT_EQ(from_bfloat16(to_bfloat16(1.0f)), 1.0f);
  EXPECT_EQ(from_bfloat16(to_bfloat16(-0.0f)), -0.0f);
  EXPECT_EQ(from_bfloat16(to_bfloat16(1.0f + 0x1.0p-8f)), 1.0f);  // tie: to even
  EXPECT_EQ(from_bfloat16(to_bfloat16(1.0f + 0x1.8p-8f)), 1.0f + 0x1.0p-7f);
}

TEST(CompressedTransport, ZeroLightGivesZeroAndRepeatsAreIdentical) {
  for (const Case& c : cases()) {
    const CompressedTransport t(c.m, c.channel_of_rgb);
    std::vector<glm::vec3> y(kN, glm::vec3(1.0f));  // stale values must be overwritten
    t.multiply(std::vector<glm::vec3>(kN, glm::vec3(0.0f)), y);
    for (const glm::vec3& v : y) ASSERT_TRUE(v == glm::vec3(0.0f)) << c.name;
    const std::vector<glm::vec3> b = random_light(kN, 12);
    std::vector<glm::vec3> first, second;
    t.multiply(b, first);
    const glm::vec3* storage = first.data();
    t.multiply(b, first);  // the right size already: not reallocated
    EXPECT_EQ(first.data(), storage) << c.name;
    t.multiply(b, second);
    EXPECT_TRUE(bitwise_equal(first, second)) << c.name;
  }
}

TEST(CompressedTransport, RejectsWrongSizesAndChannels) {
  const CompressedMatrix& m = cases()[1].m;  // three stored channels
  const CompressedTransport t(m);
  std::vector<glm::vec3> y;
  EXPECT_THROW(t.multiply(std::vector<glm::vec3>(kN - 1), y), Error);
  EXPECT_THROW(CompressedTransport(m, {0, 1, 3}), Error);
  // One stored channel serves all three colours whatever the mapping says.
  EXPECT_NO_THROW(CompressedTransport(cases()[5].m, {0, 1, 2}));
  CompressedMatrix broken = m;
  broken.blocks.pop_back();
  EXPECT_THROW(CompressedTransport{broken}, Error);
  broken = m;
  broken.permutation[0] = broken.permutation[1];
  EXPECT_THROW(CompressedTransport{broken}, Error);
  // BC4 per channel, a comparison of bounce bench compress, is no bake format.
  CodecSettings planar;
  planar.bc4_per_channel = true;
  const std::vector<std::vector<float>> small = transport_like(16, 3, 7);
  const CompressedMatrix planes = compress_matrix(pointers(small), 16, planar);
  EXPECT_THROW(CompressedTransport{planes}, Error);
}

TEST(CompressedTransport, HoleCorrectionsShareOnePatternAcrossChannels) {
  const Case& c = cases()[1];
  const CompressedTransportTables t = build_compressed_transport_tables(c.m, c.channel_of_rgb);
  std::size_t kept = 0, largest = 0;
  for (const CsrMatrix& k : c.m.kept) {
    kept += k.value.size();
    largest = std::max(largest, k.value.size());
  }
  // The union has at least the largest channel's positions, at most all.
  EXPECT_GE(t.corrections(), largest);
  EXPECT_LE(t.corrections(), kept);
  EXPECT_EQ(t.correction_value.size(), 3 * t.corrections() + 1);  // + the trailing 0
  EXPECT_EQ(t.correction_ptr.size(), t.padded + 1);
  EXPECT_EQ(t.correction_ptr.back(), t.corrections());
  std::printf("kept entries %zu over 3 channels, %zu positions\n", kept, t.corrections());
}

// The BC1 slot tables hold every block's palette: for random blocks (both
// modes, every endpoint field), the table entry the block's endpoints select
// equals decoding the block itself with libsquish-exact decode_bc1_block and
// the channel's quantizer, texel by texel.
TEST(CompressedTransport, Bc1PaletteTablesGiveEveryBlocksOwnPalette) {
  const CompressedMatrix m = random_blocks(kN, 3, DdsFormat::kBc1, 21);
  const CompressedTransportTables t = build_compressed_transport_tables(m, {0, 1, 2});
  // The tables replace per-block palettes: 2 * 2^10 * 4 floats for R and B,
  // 2 * 2^12 * 4 for G.
  EXPECT_EQ(t.bc1_tables.size(), 4u * (2048 + 8192 + 2048));
  EXPECT_TRUE(t.palettes.empty());
  std::size_t three_colour_blocks = 0;
  for (std::size_t I = 0; I < t.block_rows; ++I)
    for (std::size_t J = 0; J < t.block_rows; ++J) {
      const std::uint8_t* block = &m.blocks[(I * t.block_rows + J) * 8];
      std::uint8_t rgb[16][3];
      decode_bc1_block(block, rgb);
      three_colour_blocks += (block[0] | block[1] << 8) <= (block[2] | block[3] << 8);
      for (int s = 0; s < 3; ++s) {
        const float* palette = t.palette(I, J, s);
        for (int texel = 0; texel < 16; ++texel) {
          const int index = (block[4 + texel / 4] >> (2 * (texel % 4))) & 3;
          ASSERT_EQ(palette[index], m.quantizers[static_cast<std::size_t>(s)].decode(
                                        rgb[texel][static_cast<std::size_t>(s)]))
              << "block (" << I << ", " << J << ") slot " << s << " texel " << texel;
        }
      }
    }
  EXPECT_GT(three_colour_blocks, 0u);  // both modes were checked
  EXPECT_LT(three_colour_blocks, t.block_rows * t.block_rows);
}

TEST(ClCompressedTransport, MatchesTheDenseProductAndTheCppPath) {
  std::string why;
  if (!opencl_device(why)) GTEST_SKIP() << "no OpenCL device: " << why;
  const std::vector<glm::vec3> b = random_light(kN, 13);
  for (const Case& c : cases()) {
    const Reference r = dense_reference(c.m, c.channel_of_rgb, b);
    const ClCompressedTransport cl(c.m, c.channel_of_rgb);
    std::vector<glm::vec3> y;
    cl.multiply(b, y);
    ASSERT_EQ(y.size(), kN);
    const double worst = worst_error(y, r);
    std::printf("%-40s OpenCL: worst error / sum |T||b| = %.2e\n", c.name.c_str(), worst);
    EXPECT_LE(worst, kTolerance) << c.name << " on " << cl.device_name();
  }
}

TEST(ClCompressedTransport, ZeroLightGivesZeroAndRepeatsAreIdentical) {
  std::string why;
  if (!opencl_device(why)) GTEST_SKIP() << "no OpenCL device: " << why;
  for (const Case& c : {cases()[1], cases()[5]}) {
    const ClCompressedTransport cl(c.m, c.channel_of_rgb);
    std::vector<glm::vec3> y(kN, glm::vec3(1.0f));
    cl.multiply(std::vector<glm::vec3>(kN, glm::vec3(0.0f)), y);
    for (const glm::vec3& v : y) ASSERT_TRUE(v == glm::vec3(0.0f)) << c.name;
    const std::vector<glm::vec3> b = random_light(kN, 14);
    std::vector<glm::vec3> first, second;
    cl.multiply(b, first);
    cl.multiply(b, second);
    EXPECT_TRUE(bitwise_equal(first, second)) << c.name;
    EXPECT_THROW(cl.multiply(std::vector<glm::vec3>(kN + 1), y), Error);
  }
}

TEST(DenseTransport, MatchesADoubleProduct) {
  const std::vector<glm::vec3> b = random_light(kN, 15);
  for (int channels : {3, 1}) {
    const std::vector<std::vector<float>> t = transport_like(kN, channels, 6);
    const std::array<int, 3> map =
        channels == 3 ? std::array<int, 3>{1, 2, 0} : std::array<int, 3>{0, 0, 0};
    std::vector<glm::vec3> y;
    dense_indirect(pointers(t), kN, map, b, y);
    ASSERT_EQ(y.size(), kN);
    for (std::size_t p = 0; p < kN; ++p)
      for (int k = 0; k < 3; ++k) {
        double exact = 0.0, scale = 0.0;
        const std::vector<float>& tc =
            t[static_cast<std::size_t>(map[static_cast<std::size_t>(k)])];
        for (std::size_t q = 0; q < kN; ++q) {
          exact += static_cast<double>(tc[p * kN + q]) * b[q][k];
          scale += std::abs(static_cast<double>(tc[p * kN + q]) * b[q][k]);
        }
        ASSERT_LE(std::abs(y[p][k] - exact), kTolerance * scale) << channels << " channels";
      }
  }
  std::vector<glm::vec3> y;
  const std::vector<std::vector<float>> t = transport_like(kN, 1, 6);
  EXPECT_THROW(dense_indirect(pointers(t), kN - 1, {0, 0, 0}, b, y), Error);
}

TEST(KernelSource, EmbeddedAndOverridableFromDisk) {
  EXPECT_NE(kernel_source("compressed_transport").find("__kernel void compressed_transport"),
            std::string::npos);
  EXPECT_THROW(kernel_source("no_such_kernel"), Error);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("bounce_kernels_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "compressed_transport.cl") << "// override\n";
  ::setenv("BOUNCE_KERNEL_DIR", dir.c_str(), 1);
  const std::string overridden = kernel_source("compressed_transport");
  ::unsetenv("BOUNCE_KERNEL_DIR");
  std::filesystem::remove_all(dir);
  EXPECT_EQ(overridden, "// override\n");
}

// Every path at N = 4096 (BOUNCE_RUNTIME_BENCH_N overrides), three stored
// channels, ours at 4% kept:
//   build/release/tests/bounce_unit_tests --gtest_also_run_disabled_tests
//     --gtest_filter='*DISABLED_BenchRuntime*'
TEST(CompressedTransport, DISABLED_BenchRuntime) {
  const char* env = std::getenv("BOUNCE_RUNTIME_BENCH_N");
  const std::size_t n = env ? std::strtoul(env, nullptr, 10) : 4096;
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::vector<float>> t = transport_like(n, 3, 21);
  const CompressedMatrix m = compress_matrix(pointers(t), n, CodecSettings{});
  std::printf("synthetic %zu x %zu x 3 matrix compressed (ours, %s, %s) in %.1f s: %.1f MiB\n", n,
              n, m.encoder.c_str(), m.ordering.c_str(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
              static_cast<double>(m.total_bytes()) / (1024.0 * 1024.0));
  const RuntimeBench bench = run_runtime_bench(m, {0, 1, 2}, pointers(t), 20);
  std::printf("%s", runtime_bench_table(bench).c_str());
}

}  // namespace bounce
