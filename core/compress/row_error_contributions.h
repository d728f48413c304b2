#pragma once
// Why one patch's indirect light is wrong after compression: its row of the
// compressed matrix T~ split into the pieces the codec stores it in, each
// with what it adds to the patch's error under a light b.
//
// Patch p's indirect light is (T b)_p = sum_j T_pj b_j, and the compressed
// matrix's error there is d = sum_j (T~ - T)_pj b_j, per colour. Each entry
// (p, j) of a colour's stored channel comes from exactly one place: the kept
// (exact, CSR) entries of that channel, or the 4x4 block of the block image
// that holds stored row i (permutation[i] = p) and stored column k
// (permutation[k] = j). Grouping the terms by that place gives sources whose
// contributions add up to d exactly (in exact arithmetic), so each source's
// share of the error, dot(contribution, d) / |d|^2, adds up to 1: a block
// with a share of 0.6 makes 60% of the error, one with a negative share
// cancels part of what the others do.
#include <array>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "compress/codec.h"

namespace bounce {

// One entry (p, j) of the row, as stored and as it should be.
struct RowEntry {
  std::size_t column = 0;      // patch j
  std::size_t stored_col = 0;  // k, with permutation[k] = j
  glm::dvec3 exact{0.0};       // T_pj per colour (the colour's stored channel)
  glm::dvec3 decoded{0.0};     // T~_pj per colour
};

struct RowErrorSource {
  enum class Kind {
    Block,  // the entries of one 4x4 block that the block decodes
    Kept,   // the kept (exact) entries of one column, in the channels that keep it
  };
  Kind kind = Kind::Block;
  // The block of the stored (reordered) matrix holding the entries: block row
  // stored_row / 4, block column stored_col / 4. A kept entry lies in a
  // block too (a hole the kept value replaces).
  std::size_t block_row = 0, block_col = 0;
  // Block: up to 4 entries (the block's columns that are patches and that
  // at least one colour decodes from the block); Kept: one.
  std::vector<RowEntry> entries;
  // Per colour, the sum over the source's entries of (T~ - T)_pj b_j, counting
  // for each colour only the entries that come from this source.
  glm::dvec3 contribution{0.0};
  // dot(contribution, d) / |d|^2; 0 when d is 0.
  double share = 0.0;
};

struct RowErrorContributions {
  std::size_t patch = 0;
  std::size_t stored_row = 0;  // i, with permutation[i] = patch
  glm::dvec3 exact{0.0};       // (T b)_p per colour
  glm::dvec3 compressed{0.0};  // (T~ b)_p per colour
  glm::dvec3 difference{0.0};  // compressed - exact = sum of the contributions
  // Every source of the row with a nonzero entry or a nonzero contribution,
  // largest share first (ties: larger |contribution| first).
  std::vector<RowErrorSource> sources;
};

// `m`: the compressed matrix; `exact`: its m.channels exact matrices (n x n,
// row-major, patch order); `channel_of_rgb[k]`: the stored channel colour k
// uses; `b`: the light leaving each patch after the first hit (n). Throws
// bounce::Error when the patch, light or channels do not fit the matrix.
RowErrorContributions row_error_contributions(const CompressedMatrix& m,
                                              const std::vector<const float*>& exact,
                                              const std::array<int, 3>& channel_of_rgb,
                                              const std::vector<glm::vec3>& b, std::size_t patch);

}  // namespace bounce
