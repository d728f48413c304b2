#pragma once
// An encoder-independent figure of merit for a reordering: how much the codes
// inside each 4x4 block (the BC1 block) differ. BC1 spends two endpoints and
// sixteen 2-bit indices per block, so its error grows with the spread of the
// sixteen values around their centre; a reordering that puts similar rows
// and columns in the same quads lowers it.
//
//   cost = sum over 4x4 blocks of the permuted image,
//          sum over channels, sum over the block's pixels of |code - block mean|
//
// Blocks on the right and bottom edges of an image whose side is not a
// multiple of 4 count only the pixels they have (BC1 pads them by repetition,
// which adds no spread).
//
// Holes: the compression keeps the largest entries exactly and leaves code 0
// ("holes") in their place, which the block encoder treats as don't-care
// (weight 0, compress/block_bc1.h). With zero_is_hole, codes 0 are left out
// of the figure (mean and spread over the other texels of the block and
// channel), which is what the encoder sees; without it they count as 0.
#include <cstddef>
#include <cstdint>

#include "compress/ordering_permutation.h"

namespace bounce {

// `perm` as in apply_symmetric (permuted[i][j] = image[perm[i]][perm[j]]);
// empty means identity. Deterministic (fixed summation order), OpenMP-parallel,
// no copy of the image.
double block_spread_cost(const std::uint8_t* image, std::size_t n, std::size_t channels,
                         const Permutation& perm = {}, bool zero_is_hole = false);

}  // namespace bounce
