#pragma once
// The run-time product of the compressed multi-bounce matrix on the CPU
// (DESIGN 1.8, issue 4 section 2): for each colour channel k,
//   indirect_k = T~_c(k) b_k,
// with T~ the matrix decompress_channel() gives (kept entries exact, the rest
// decoded from the blocks), computed straight from the blocks: the dense
// matrix is never formed. Equal to the dense product of decompress_channel's
// output up to float32 summation order.
//
// Per product: b is gathered into stored (permuted) order once, every block
// row is multiplied (OpenMP over bands of 8 block rows; per block, the 2- or 3-bit
// indices select values from the block's palette, see
// runtime/compressed_transport_tables.h), the corrections of the kept
// entries are added to the same row accumulators, and the rows are scattered
// back to patch order. With AVX2 (checked at run time), one block is a few
// vector permutes and FMAs: the indices of two block rows become the control
// of one permute of the palette, 8 texels at once; without it a portable
// loop does the same one texel at a time.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "compress/codec.h"
#include "runtime/compressed_transport_tables.h"

namespace bounce {

// The block loop: the fastest float32 loop this CPU runs (AVX-512 for BC1,
// else AVX2, else portable), AVX2 at most, or the portable one (the last two
// for tests of the slower loops on CPUs that would take a faster one).
// kBf16: BC1 products in bfloat16 with float32 sums (AVX-512 BF16 + VBMI;
// has_bf16_loop() tells; else as kFastest): palettes and b are rounded to
// 8-bit mantissas, a relative error of at most 2^-8 of sum |T~||b| per row
// (measured ~5e-4 mean on the Cornell box, 30x below the compression error),
// for fewer instructions per block (docs/benchmarks.md).
enum class BlockLoop { kFastest, kAvx2, kPortable, kBf16 };

// float <-> bfloat16 (the top 16 bits of a float32), rounding to nearest even;
// for finite values.
std::uint16_t to_bfloat16(float x);
float from_bfloat16(std::uint16_t h);

// Two neighbouring BC1 blocks (J, J + 1) of a block row as the AVX-512
// loops read them: both index words (bytes 4-7 of each block), then per
// block and colour (R, G, B) where its palette is in the tables (the table
// of the colour's slot at the key of the block's endpoints, in units of 8
// bytes: one bfloat16 palette, half a float32 one), computed once when the
// object is built rather than at every product. 20 bytes for two blocks
// (the DDS has 16). A block row with an odd block count ends with a pair
// whose second block has zero indices and the first block's palettes. The
// records are stored in the order the loops read them (bands of block rows,
// tiles of b; compressed_transport.cpp), not row by row.
struct Bc1BlockPair {
  std::uint32_t indices[2];
  std::uint16_t palette[2][3];
};
static_assert(sizeof(Bc1BlockPair) == 20);

class CompressedTransport {
 public:
  // Lays the matrix out once (see build_compressed_transport_tables, whose
  // errors it throws). channel_of_rgb: stored channel of R, G, B.
  explicit CompressedTransport(const CompressedMatrix& m,
                               const std::array<int, 3>& channel_of_rgb = {0, 1, 2},
                               BlockLoop loop = BlockLoop::kFastest);
  explicit CompressedTransport(CompressedTransportTables tables,
                               BlockLoop loop = BlockLoop::kFastest);

  // indirect[p] = (T~_c(0) b_0, T~_c(1) b_1, T~_c(2) b_2)[p] for every patch
  // p. b has one entry per patch (throws bounce::Error otherwise); indirect
  // is resized only when its size differs, and nothing else is allocated.
  // Uses a scratch buffer of the object: one call at a time per object.
  void multiply(const std::vector<glm::vec3>& b, std::vector<glm::vec3>& indirect) const;
  // The same into caller-owned memory (e.g. a frame graph's arena): both
  // spans one entry per patch, throws bounce::Error otherwise. b must not
  // overlap indirect.
  void multiply(std::span<const glm::vec3> b, std::span<glm::vec3> indirect) const;

  std::size_t size() const { return tables_.n; }
  const CompressedTransportTables& tables() const { return tables_; }
  // Bytes one product reads: the tables plus b (in patch order, 12 per patch).
  std::size_t bytes_per_product() const;
  // "avx512-bf16", "avx512", "avx2" or "portable": the block loop multiply() runs.
  const char* block_loop() const;
  // Whether this CPU runs the bfloat16 loop (BlockLoop::kBf16).
  static bool has_bf16_loop();

 private:
  CompressedTransportTables tables_;
  bool avx2_ = false;    // AVX2 block loop and corrections
  bool avx512_ = false;  // AVX-512 block loop (BC1)
  bool bf16_ = false;    // AVX-512 bfloat16 block loop (BC1)
  // The BC1 blocks as the AVX-512 loops read them, pairs_per_row_ per
  // block row (avx512_ and BC1 only; see Bc1BlockPair): 20 bytes per 16 of
  // the DDS, held besides tables_.blocks (which the OpenCL path reads).
  std::vector<Bc1BlockPair> block_pairs_;
  std::size_t pairs_per_row_ = 0;
  void lay_out_block_pairs();
  // BC1 palette tables rounded to bfloat16 (bf16_ only), same layout.
  std::vector<std::uint16_t> bc1_tables16_;
  // b in stored order, padding columns 0, twice: colour-major (R of every
  // stored column, then G, then B), the block loop reads 4 columns of one
  // colour at once; and R, G, B, 0 per column, a kept entry reads its column's
  // 3 colours at once.
  mutable std::vector<float> b_stored_;
  mutable std::vector<float> b_quad_;
  // bf16_ only: b_stored_ rounded to bfloat16, padded + 8 entries per colour.
  mutable std::vector<std::uint16_t> b16_;
};

}  // namespace bounce
