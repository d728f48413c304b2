#pragma once
// The run-time product of the compressed multi-bounce matrix on the CPU
// (the run-time product): for each colour channel k,
//   indirect_k = T~_c(k) b_k,
// with T~ the matrix decompress_channel() gives (kept entries exact, the rest
// decoded from the blocks), computed straight from the blocks: the dense
// matrix is never formed. Equal to the dense product of decompress_channel's
// output up to float32 summation order.
//
// Per product, in one parallel region: b is gathered into stored (permuted)
// order (and for the bfloat16 loop rounded) on all threads, every block row
// is multiplied (OpenMP over bands of 8 block rows; per block, the 2- or
// 3-bit indices select values from the block's palette, see
// compress/compressed_transport_tables.h) into a stored-order buffer, then
// the corrections of the kept entries are added and the rows scattered back
// to patch order. The corrections run as a pass of their own after the
// block loop: run between its bands, their random reads of b evicted the
// band's working set (docs/benchmarks.md, `bounce bench runtime`). With AVX2 (checked
// at run time), one block is a few vector permutes and FMAs: the indices of
// two block rows become the control of one permute of the palette, 8 texels
// at once; without it a portable loop does the same one texel at a time.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "compress/codec.h"
#include "compress/compressed_transport_tables.h"

namespace bounce {

// The block loop. kFastest, the default: for BC1 the bfloat16 loop where
// the CPU has it (AVX-512 BF16 + VBMI; has_bf16_loop() tells), else as
// kFloat32. Its palettes and b are rounded to 8-bit mantissas, a relative
// error of at most 2^-8 of sum |T~||b| per row (9e-4 of the largest entry
// on the 8465-patch Cornell box, 170x below the compression error there;
// docs/benchmarks.md, runtime), for about half the instructions per block.
// kFloat32: the fastest float32 loop this CPU runs (AVX-512 for BC1, else
// AVX2, else portable), equal to the dense product of the decompressed
// matrix up to float32 summation order. kAvx2 (AVX2 at most) and kPortable
// are for tests of the slower loops on CPUs that would take a faster one.
enum class BlockLoop { kFastest, kFloat32, kAvx2, kPortable };

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
// tiles of b; runtime/block_loops.h), not row by row.
struct Bc1BlockPair {
  std::uint32_t indices[2];
  std::uint16_t palette[2][3];
};
static_assert(sizeof(Bc1BlockPair) == 20);

// Eight neighbouring BC1 blocks (8G .. 8G + 7) of a block row as the
// bfloat16 loop reads them: the 8 index words, then per colour (R, G, B) the
// 8 blocks' palettes in the bfloat16 tables (in units of 8 bytes, one
// palette each). 80 bytes for 8 blocks, 10 per block as in Bc1BlockPair. A
// block row is padded to a multiple of 8 blocks with blocks of zero indices
// and the last block's palettes, whose b is zero. Stored in loop order as
// the pairs are (runtime/block_loops.h).
struct Bc1BlockGroup {
  std::uint32_t indices[8];
  std::uint16_t palette[3][8];
};
static_assert(sizeof(Bc1BlockGroup) == 80);

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
  // Whether this CPU runs the bfloat16 loop (BlockLoop::kFastest for BC1).
  static bool has_bf16_loop();

 private:
  CompressedTransportTables tables_;
  bool avx2_ = false;    // AVX2 block loop and corrections
  bool avx512_ = false;  // AVX-512 block loop (BC1)
  bool bf16_ = false;    // AVX-512 bfloat16 block loop (BC1)
  // The BC1 blocks as the AVX-512 loops read them, held besides
  // tables_.blocks (which the OpenCL path reads), 10 bytes per block (8 in
  // the DDS):
  // the float32 loop's pairs_per_row_ pairs per block row (avx512_, BC1,
  // not bf16_; see Bc1BlockPair), or the bfloat16 loop's groups_per_row_
  // groups of 8 (bf16_; see Bc1BlockGroup).
  std::vector<Bc1BlockPair> block_pairs_;
  std::size_t pairs_per_row_ = 0;
  void lay_out_block_pairs();
  std::vector<Bc1BlockGroup> block_groups_;
  std::size_t groups_per_row_ = 0;
  void lay_out_block_groups();
  // BC1 palette tables rounded to bfloat16 (bf16_ only), same layout.
  std::vector<std::uint16_t> bc1_tables16_;
  // b in stored order, padding columns 0, twice: colour-major (R of every
  // stored column, then G, then B), the block loop reads 4 columns of one
  // colour at once (not filled for the bfloat16 loop, which reads b16_); and
  // R, G, B, 0 per column, a kept entry reads its column's 3 colours at once.
  mutable std::vector<float> b_stored_;
  mutable std::vector<float> b_quad_;
  // bf16_ only: b in stored order rounded to bfloat16, colour-major,
  // 32 * groups_per_row_ entries per colour (zero past n), starting at
  // b16_start_, the first 64-byte boundary in the vector (the loop reads 32
  // columns at once; an unaligned 64-byte load spans two cache lines).
  mutable std::vector<std::uint16_t> b16_;
  std::size_t b16_start_ = 0;
  // The block loop's row sums in stored order (3 per stored row), to which
  // the corrections pass adds the kept entries.
  mutable std::vector<float> y_stored_;
};

}  // namespace bounce
