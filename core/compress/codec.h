#pragma once
// The compressed multi-bounce matrix (the published pipeline, and ours):
// largest entries kept (CSR), the rest log-quantised to 8-bit codes, rows
// and columns reordered by one permutation, block-encoded.
//
//   paper: 4% kept per channel exactly (float32), codes of T_R, T_G, T_B in R, G, B, the
//          paper's greedy L1 tour (2 passes), BC1 by libsquish cluster fit.
//          Kept forever as the baseline.
//   ours:  the same kept split, then our ordering (sketch + tour + 4-row
//          refinement) and our encoders, which minimise the error after the
//          inverse log step (weights ~ value^2) and ignore the holes left by
//          kept entries: BC1 weighted for colour scenes, BC4 weighted (same
//          8 bytes per 4x4 block, one channel at full 8-bit endpoints) for
//          grey scenes, whose single channel does not need RGB. Given an
//          EntryImportance (how much each entry's error shows in the
//          indirect light), ours keeps the entries whose error would show
//          most instead of the largest ones, and the encoder weighs every
//          texel by it too: the bytes go where the light goes. Ours stores
//          the kept entries in half precision with 16-bit columns
//          (compress/kept_storage.h): twice the entries in the same bytes.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "base/progress.h"
#include "compress/block_bc1.h"
#include "compress/block_bc4.h"
#include "compress/dds.h"
#include "compress/entry_importance.h"
#include "compress/kept_storage.h"
#include "compress/log_quantizer.h"
#include "compress/ordering_permutation.h"
#include "compress/sparse_split.h"

namespace bounce {

// LargestEntries: the published pipeline ("paper" above); LightWeighted:
// ours, which with an EntryImportance keeps and weighs entries by the light
// they carry ("ours"). codec_name gives the names the CLI and manifest use.
enum class CodecKind { LargestEntries, LightWeighted };

// The published pipeline keeps this share of each channel's largest entries
// exactly (4%); `--codec paper` keeps it unless told otherwise.
inline constexpr double kPaperKeptFraction = 0.04;
// How rows and columns are reordered before block encoding (the CLI and the
// manifest keep the names ordering_name gives):
//   GreedyRowTour: the published greedy nearest-neighbour tour over rows
//     (ordering_paper.h, one pass, "paper-1-pass");
//   GreedyRowThenColumnTour: that tour, then the same over columns ("paper-2-passes");
//   SketchTour: row sketches, k nearest neighbours, a tour improved by 2-opt
//     and Or-opt, block rows refined (ordering.h, "ours").
enum class OrderingMethod { None, GreedyRowTour, GreedyRowThenColumnTour, SketchTour };

struct CodecSettings {
  CodecKind kind = CodecKind::LightWeighted;
  double kept_fraction = kPaperKeptFraction;
  // Overrides, for comparisons (bounce bench compress); unset = the codec's own.
  std::optional<Bc1Encoder> bc1_encoder;
  // Colour scenes: one BC4 image per channel (3 x 8 bytes per block, 3x the
  // block bytes of BC1) instead of one BC1 image, for the comparison in
  // bounce bench compress. Not a bake format: the DDS holds one image.
  bool bc4_per_channel = false;
  std::optional<OrderingMethod> ordering;
  // How the kept entries are stored; unset: float16 for ours, float32 for
  // the paper.
  std::optional<KeptStorage> kept_storage;
  // Ours only: which entries matter to the light (not owned; must outlive
  // compress_matrix). Null: the largest entries are kept and the encoder
  // weighs only by value.
  const EntryImportance* importance = nullptr;
  // Ours with an importance: compress this many times, each pass after the
  // first keeping the entries the previous pass's blocks decoded worst
  // (weighted), with the first pass's ordering. The block error is far from
  // proportional to the value (a block of similar codes is almost exact, one
  // of mixed codes is not).
  int kept_passes = 2;
  // A permutation computed before (CompressedMatrix::permutation of an earlier
  // run on the same matrices, kind, kept fraction and channel count: the
  // codes it was computed on depend on all four), used instead
  // of computing `ordering` again: the paper's tour is O(n^3), and a
  // comparison of encoders should not pay for it once per encoder. The report
  // still names `ordering`; seconds_ordering is then 0. Must be a bijection
  // of 0..n-1 (compress_matrix throws bounce::Error otherwise).
  std::optional<Permutation> permutation;
  // A sample of the stored image's block rows (ascending, each below
  // padded / 4; needs `permutation`): only the patches of those rows are
  // split, quantised and encoded, the kept threshold keeping the same share of
  // their entries. The error budget's search measures kept fractions on such
  // a sample, whose light error estimates the whole matrix's at a fraction of
  // the encoding. Empty: every block row.
  std::vector<std::uint32_t> block_rows;
};

struct CompressedMatrix {
  std::size_t n = 0;       // patches
  std::size_t padded = 0;  // n rounded up to a multiple of 4
  int channels = 3;        // matrices stored: 1 (grey scene) or 3 (R, G, B)
  DdsFormat format = DdsFormat::kBc1;
  Permutation permutation;               // stored row/column k holds patch permutation[k]
  std::vector<LogQuantizer> quantizers;  // per stored channel
  std::vector<CsrMatrix> kept;           // per stored channel, patch order
  // How the bake folder stores `kept`; float16: its values are halves.
  KeptStorage kept_storage = KeptStorage::kFloat32;
  // padded/4 x padded/4 blocks of 8 bytes (BC4 per channel: one such image
  // per stored channel, one after another).
  std::vector<std::uint8_t> blocks;
  // What was used, for reports.
  std::string codec, encoder, ordering;
  double kept_fraction = 0.0;
  bool light_weighted = false;  // kept entries and block weights chosen by EntryImportance
  int kept_passes = 1;          // CodecSettings::kept_passes, as used
  // The importance weighted each light by its share of an earlier
  // compression's light error (bake/matrix_storage.h).
  bool lights_rebalanced = false;
  // A rebalanced compression was made and measured (light_rebalance.h: only
  // when the worst light's error stood out from the mean).
  bool lights_rebalance_tried = false;
  double seconds_split = 0.0, seconds_ordering = 0.0, seconds_encoding = 0.0;
  // Blocks encoded over all kept passes (a later pass encodes only the
  // blocks whose kept entries changed).
  std::size_t blocks_encoded = 0;
  // Empty: `blocks` holds every block row of the image. Otherwise the block
  // rows it holds, in this order (CodecSettings::block_rows): the matrix is
  // then known on rows() only, an estimate that is never stored.
  std::vector<std::uint32_t> block_rows;

  bool sampled() const { return !block_rows.empty(); }
  // The patches whose rows the blocks hold, ascending: every patch unless
  // sampled.
  std::vector<std::uint32_t> rows() const;

  std::size_t sparse_bytes() const;
  std::size_t block_bytes() const { return blocks.size(); }
  std::size_t permutation_bytes() const { return permutation.size() * sizeof(std::uint32_t); }
  std::size_t total_bytes() const { return sparse_bytes() + block_bytes() + permutation_bytes(); }
};

// How compress_matrix encodes its padded, permuted image of codes (its last
// step): width x width texels of texel_channels() codes each, with a weight
// per code. Blocks are independent and each is encoded deterministically, so
// the image can be encoded by block rows anywhere (a distributed bake shares
// them among its processes) with the same bytes as in one piece.
struct BlockEncoding {
  std::size_t width = 0;  // the padded matrix size, a multiple of 4
  DdsFormat format = DdsFormat::kBc1;
  Bc1Encoder bc1 = Bc1Encoder::kWeighted;  // BC1 only (BC4 is always weighted)
  // BC4 per channel: three channels per texel, one BC4 image each, stored one
  // after another.
  bool bc4_per_channel = false;

  std::size_t texel_channels() const {
    return format == DdsFormat::kBc4 && !bc4_per_channel ? 1 : 3;
  }
  std::size_t block_rows() const { return width / 4; }
  // Bytes of one block row of one image (width / 4 blocks of 8 bytes).
  std::size_t block_row_bytes() const { return width / 4 * 8; }
  std::size_t images() const { return bc4_per_channel ? 3 : 1; }
};

// Encodes `count` block rows given only their texels (`codes`, `weights`:
// 4 count rows of width x texel_channels() each): their blocks in image
// order, and for BC4 per channel each channel's blocks, channel after channel.
std::vector<std::uint8_t> encode_block_rows(const BlockEncoding& e, std::size_t count,
                                            std::span<const std::uint8_t> codes,
                                            std::span<const float> weights);
// Copies block rows first .. first + count - 1, as encode_block_rows returns
// them, into their places among the whole image's blocks (images() x
// block_rows() x block_row_bytes() bytes).
void place_block_rows(const BlockEncoding& e, std::size_t first, std::size_t count,
                      std::span<const std::uint8_t> rows, std::span<std::uint8_t> blocks);

// Where compress_matrix encodes its blocks: in this process when none is
// given; a distributed bake's executor (core/distributed) encodes the block
// rows on all its processes and gathers them, with the same bytes.
class CompressionExecutor {
 public:
  virtual ~CompressionExecutor() = default;
  // The whole image's blocks (see place_block_rows), as
  // encode_block_rows(e, e.block_rows(), codes, weights) returns them.
  virtual std::vector<std::uint8_t> encode_blocks(const BlockEncoding& e,
                                                  std::span<const std::uint8_t> codes,
                                                  std::span<const float> weights) = 0;
  virtual std::string description() const = 0;
};

// What compress_matrix will spend on `channels` stored channels of n x n at
// `kept_fraction` with one block image: kept CSR in `storage` (at most that
// share of every channel; fewer when a channel has fewer positive entries) +
// blocks + permutation. An upper bound, exact unless entries tie at the
// threshold.
std::size_t predicted_total_bytes(std::size_t n, int channels, double kept_fraction,
                                  KeptStorage storage);

// `matrices`: 1 or 3 row-major n x n float32 matrices (T_R, T_G, T_B, or the
// one matrix of a grey scene).
CompressedMatrix compress_matrix(const std::vector<const float*>& matrices, std::size_t n,
                                 const CodecSettings& settings, Progress* progress = nullptr,
                                 CompressionExecutor* executor = nullptr);

// Stored channel c back to dense rows in patch order (kept entries exact, the
// rest decoded from the blocks, the permutation undone): m.rows().size() x n
// values, row k for patch m.rows()[k] (n x n in patch order unless sampled).
void decompress_channel(const CompressedMatrix& m, int c, float* out);
// The same without the kept entries: what the blocks hold everywhere, holes
// included.
void decode_blocks_of_channel(const CompressedMatrix& m, int c, float* out);

// The permutation compress_matrix would compute for `settings` (its split and
// ordering, no encoding), for reuse through CodecSettings::permutation.
Permutation compute_permutation(const std::vector<const float*>& matrices, std::size_t n,
                                const CodecSettings& settings, Progress* progress = nullptr);

const char* codec_name(CodecKind kind);
const char* ordering_name(OrderingMethod method);

}  // namespace bounce
