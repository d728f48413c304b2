#pragma once
// The compression stage's block encoding on every rank of the MPI job
// (compression by row blocks, the ordering computed once).
//
// The root runs compress_matrix as one process does: the kept split and the
// quantisers (global: a quantile per channel over the whole matrix) and the
// ordering (from a sketch of all rows) are computed there, once per
// compression tried. Only the encoding of the permuted image is shared: the
// root broadcasts a small command (image width, format, encoder), sends each
// rank one contiguous range of block rows (rank r: block rows
// r B / R .. (r + 1) B / R - 1 of B; their codes and weights, already permuted,
// so no rank needs the permutation or T), encodes its own range, and copies
// every rank's blocks into place. A block depends on its 16 texels alone and
// every encoder is deterministic, so the gathered image is the one process's
// byte for byte.
//
// A rank whose encoding fails (an exception) reports it to the root instead
// of blocks and keeps serving; the root collects every rank's answer, then
// throws one error naming the rank, so the bake fails before anything is
// written.
#include <memory>

#include "compress/codec.h"

namespace bounce {

// Block rows first .. end - 1 of `block_rows` that rank `rank` of `ranks`
// encodes.
struct BlockRowRange {
  std::size_t first = 0, end = 0;
  std::size_t count() const { return end - first; }
};
BlockRowRange block_rows_of_rank(std::size_t rank, std::size_t ranks, std::size_t block_rows);

// Root: the executor compress_matrix uses. Collective with
// serve_mpi_compression on the other ranks; its destructor releases them.
std::unique_ptr<CompressionExecutor> make_mpi_compression_executor();

// Not the root: encodes the block rows the root sends until its executor is
// destroyed.
void serve_mpi_compression();

}  // namespace bounce
