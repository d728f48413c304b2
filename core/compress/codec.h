#pragma once
// The compressed multi-bounce matrix (paper 000, section 4.2, and ours):
// largest entries kept exactly (CSR, float32), the rest log-quantised to
// 8-bit codes, rows and columns reordered by one permutation, block-encoded.
//
//   paper: 4% kept per channel, codes of T_R, T_G, T_B in R, G, B, the
//          paper's greedy L1 tour (2 passes), BC1 by libsquish cluster fit.
//          Kept forever as the baseline.
//   ours:  the same kept split, then our ordering (sketch + tour + 4-row
//          refinement) and our encoders, which minimise the error after the
//          inverse log step (weights ~ value^2) and ignore the holes left by
//          kept entries: BC1 weighted for colour scenes, BC4 weighted (same
//          8 bytes per 4x4 block, one channel at full 8-bit endpoints) for
//          grey scenes, whose single channel does not need RGB.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/progress.h"
#include "compress/block_bc1.h"
#include "compress/block_bc4.h"
#include "compress/dds.h"
#include "compress/log_quantizer.h"
#include "compress/ordering_permutation.h"
#include "compress/sparse_split.h"

namespace bounce {

enum class CodecKind { Paper, Ours };
enum class OrderingMethod { None, Paper1, Paper2, Ours };

struct CodecSettings {
  CodecKind kind = CodecKind::Ours;
  double kept_fraction = 0.04;
  // Overrides, for comparisons (bounce bench compress); unset = the codec's own.
  std::optional<Bc1Encoder> bc1_encoder;
  // Colour scenes: one BC4 image per channel (3 x 8 bytes per block, 3x the
  // block bytes of BC1) instead of one BC1 image, for the comparison in
  // bounce bench compress. Not a bake format: the DDS holds one image.
  bool bc4_per_channel = false;
  std::optional<OrderingMethod> ordering;
  // A permutation computed before (CompressedMatrix::permutation of an earlier
  // run on the same matrices, kind, kept fraction and channel count: the
  // codes it was computed on depend on all four), used instead
  // of computing `ordering` again: the paper's tour is O(n^3), and a
  // comparison of encoders should not pay for it once per encoder. The report
  // still names `ordering`; seconds_ordering is then 0. Must be a bijection
  // of 0..n-1 (compress_matrix throws bounce::Error otherwise).
  std::optional<Permutation> permutation;
};

struct CompressedMatrix {
  std::size_t n = 0;       // patches
  std::size_t padded = 0;  // n rounded up to a multiple of 4
  int channels = 3;        // matrices stored: 1 (grey scene) or 3 (R, G, B)
  DdsFormat format = DdsFormat::kBc1;
  Permutation permutation;               // stored row/column k holds patch permutation[k]
  std::vector<LogQuantizer> quantizers;  // per stored channel
  std::vector<CsrMatrix> kept;           // per stored channel, patch order
  // padded/4 x padded/4 blocks of 8 bytes (BC4 per channel: one such image
  // per stored channel, one after another).
  std::vector<std::uint8_t> blocks;
  // What was used, for reports.
  std::string codec, encoder, ordering;
  double kept_fraction = 0.0;
  double seconds_split = 0.0, seconds_ordering = 0.0, seconds_encoding = 0.0;

  std::size_t sparse_bytes() const;
  std::size_t block_bytes() const { return blocks.size(); }
  std::size_t permutation_bytes() const { return permutation.size() * sizeof(std::uint32_t); }
  std::size_t total_bytes() const { return sparse_bytes() + block_bytes() + permutation_bytes(); }
};

// `matrices`: 1 or 3 row-major n x n float32 matrices (T_R, T_G, T_B, or the
// one matrix of a grey scene).
CompressedMatrix compress_matrix(const std::vector<const float*>& matrices, std::size_t n,
                                 const CodecSettings& settings, Progress* progress = nullptr);

// Stored channel c back to a dense n x n matrix in patch order (kept entries
// exact, the rest decoded from the blocks, the permutation undone).
void decompress_channel(const CompressedMatrix& m, int c, float* out);

const char* codec_name(CodecKind kind);
const char* ordering_name(OrderingMethod method);

}  // namespace bounce
