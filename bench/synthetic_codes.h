#pragma once
// A large synthetic "transport image" for `bounce bench ordering`: the
// log-quantised codes of a light-exchange kernel between patches on three
// walls of a unit box (floor, back, left), as in the ordering unit tests:
//   ln v_ij = -|x_i - x_j| / 0.2 + 5% log-normal-ish noise (sum of 4 uniforms),
// channel c scaled by (1 - 0.1 c) like the R, G, B of a coloured room. The
// largest `kept_fraction` of the values become holes (code 0), as the kept
// split of the compression leaves them; the rest is quantised as in
// compress/log_quantizer.h with vmax = the largest value that is not a hole.
//
// Patch i of the *structured* order sits on wall 3i/n, on a serpentine walk
// over a grid of cells of that wall, so that neighbouring indices are
// neighbours in space: its image is already well ordered. The image returned
// is that one shuffled by a random permutation (rows and columns together),
// like patches in voxel order, and `structure` is the permutation that
// restores the structured order (apply_symmetric(image, structure) is it).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "compress/ordering_permutation.h"

namespace bounce {

struct SyntheticCodes {
  std::size_t n = 0;
  std::size_t channels = 0;
  std::vector<std::uint8_t> image;  // n x n x channels, shuffled order
  Permutation structure;            // shuffled -> structured order
  double hole_fraction = 0.0;       // share of entries that are holes (code 0)
  double seconds = 0.0;             // generation time
};

// Deterministic for a seed, whatever the thread count (one random stream per
// row). Runs on every hardware thread.
SyntheticCodes synthetic_codes(std::size_t n, std::size_t channels, double kept_fraction,
                               std::uint64_t seed);

}  // namespace bounce
