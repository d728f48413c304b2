#pragma once
// Reading a compressed multi-bounce matrix T~ (compress/compressed_transport_
// tables.h: BC1/BC4 blocks plus kept entries, stored order) by block
// columns instead of whole: what light-importance temporal radiosity
// (dynamic/light_temporal_radiosity.h) multiplies each frame. A block
// column is 4 stored columns, one 8-byte block per block row (nb = block
// rows); a chosen block column is read from a block-column-major copy of
// the blocks and the kept entries of its 4 columns from a by-column copy of
// the kept entries.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "compress/compressed_transport_tables.h"

namespace bounce {

// Per stored column q and colour k (R, G, B): sum over rows of |T~_pq| of
// the stored channel colour k uses, kept entries included; 3 * padded floats,
// padding columns 0. One pass over the whole matrix (O(n^2), done once).
std::vector<float> compressed_column_abs_sums(const CompressedTransportTables& t);

// The kept entries' corrections (kept - decoded, per colour) by stored
// column: the tables hold them by row, where finding a few columns' entries
// means searching every row; by column, a drawn column's entries are one
// contiguous run. Same size as the row form (one index and `width` values
// per entry).
struct KeptColumns {
  int width = 3;                   // values per entry: R, G, B, or 1 for all
  std::vector<std::uint32_t> ptr;  // padded + 1 offsets
  std::vector<std::uint32_t> row;  // stored row per entry
  std::vector<float> value;        // width per entry, then one trailing 0
  std::size_t bytes() const {
    return (ptr.size() + row.size()) * sizeof(std::uint32_t) + value.size() * sizeof(float);
  }
};
KeptColumns kept_by_column(const CompressedTransportTables& t);

// The blocks in block-column-major order (block (I, J) at J * nb + I, 8
// bytes each): a drawn block column is then one sequential run of nb
// blocks instead of nb reads nb * 8 bytes apart, each on a cache line of
// its own. Same size as the tables' blocks.
std::vector<std::uint8_t> blocks_by_column(const CompressedTransportTables& t);

// y[i][k] = sum over stored columns q of the block columns in `block_columns`
// (ascending, each once) of B_iq x[q][k], for every stored row i (padded
// rows; y[i][3] = 0), B the matrix the blocks decode to (without the kept
// entries). x: 4 floats per stored column (R, G, B, unused), padded
// columns; columns outside `block_columns` are not read.
// `column_blocks`: blocks_by_column(t) (the palettes come from t).
void multiply_block_columns(const CompressedTransportTables& t, const std::uint8_t* column_blocks,
                            const float* x, std::span<const std::uint32_t> block_columns,
                            float (*y)[4]);
// Adds the kept entries' corrections of those block columns: after both,
// y = T~ restricted to the block columns, times x. Returns the entries added.
std::size_t add_kept_columns(const KeptColumns& kept, const float* x,
                             std::span<const std::uint32_t> block_columns, float (*y)[4]);

}  // namespace bounce
