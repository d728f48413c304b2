#pragma once
// Re-encoding only what a kept pass changed. A later kept pass of
// compress_matrix keeps the permutation, the quantisers and the importance of
// the pass before it, so a texel's code and weight depend only on whether its
// entry is kept (a hole) or not. A block whose 16 texels keep their hole
// status in every channel has the same texels, and the deterministic encoder
// gives it the same 8 bytes: only the blocks where an entry moved in or out
// of the kept set need encoding again.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "compress/codec.h"

namespace bounce {

// Indices into `after`'s blocks (sample slot x blocks per row + block column)
// of the blocks holding an entry kept by one compression and not the other.
// Both must share n, permutation, block rows and channels.
std::vector<std::size_t> blocks_with_changed_holes(const CompressedMatrix& before,
                                                   const CompressedMatrix& after);

// Encodes blocks `which` of `m` into m.blocks from the texels in patch order
// (`codes`, `weights`: rows x n x `channels`, as compress_matrix splits them),
// through m.permutation, exactly as the whole image's encoding would. Patch
// row i's texels are texel row `row_slot[i]` (empty: row i; a sample holds
// its own rows only). One image only (BC1, or BC4 of a grey scene).
void encode_blocks_in_place(const BlockEncoding& e, std::span<const std::size_t> which,
                            std::span<const std::uint8_t> codes, std::span<const float> weights,
                            std::size_t channels, CompressedMatrix& m,
                            std::span<const std::uint32_t> row_slot = {});

}  // namespace bounce
