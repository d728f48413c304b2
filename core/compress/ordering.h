#pragma once
// Reordering of the quantised transport image before BC1 (as the
// published compression does): one permutation of rows and columns that puts patches with
// similar rows (and columns) into the same 4x4 blocks.
//
//   paper_ordering()  the published greedy L1 tour, O(n^3): the baseline,
//                     kept exactly as printed (ordering_paper.h).
//   our_ordering()    O(n^2 (dims + oversampling)) flops for the sketch (two
//                     reads of the image) and O(n^2 dims) for the neighbour
//                     search; the rest is O(n k dims) per sweep:
//     1. principal sketch of each patch's row and column (ordering_sketch.h):
//        two passes over the image, sgemm;
//     2. k nearest neighbours of every sketch (ordering_knn.h);
//     3. greedy nearest-neighbour tour on the sketches, 2-opt + Or-opt on
//        candidate lists, cut at the longest edge (ordering_tour.h);
//     4. block-aware refinement: swaps and chains of moves between groups of
//        four that tighten each group, since only the grouping into fours
//        matters to BC1 (ordering_quads.h).
//   Measured on the wall-kernel test matrix (random patch order): block
//   spread 0.079 / 0.063 / 0.047 of the unordered image at n = 2048 / 4096 /
//   16384, against 0.100-0.104 / 0.077-0.080 / 0.051 for the paper's tour
//   (1-2 passes; one pass at 16384). CPU time 0.42 / 1.33 / 17.7 s on one
//   core (the paper's: 0.29-0.79 / 2.0-5.3 / ~120 s per pass); n = 16384
//   took 27-37 s wall with 2 threads on the shared machine (load 4-6).
//   block_spread_cost() compares orderings without an encoder
//                     (ordering_cost.h).
#include <cstddef>
#include <cstdint>

#include "compress/ordering_cost.h"
#include "compress/ordering_paper.h"
#include "compress/ordering_permutation.h"
#include "compress/ordering_sketch.h"

namespace bounce {

struct OrderingSettings {
  // Step 1. dims = 32 keeps > 99% of the centred energy of smooth transport
  // images in tests. `use_columns` matters when the matrix is not symmetric:
  // a form factor carries the receiver's area (F_ij ~ A_j K_ij), a shift per
  // column in log codes that row distances cannot see but every 4x4 block
  // does (measured with random areas: 0.144 of the unordered spread with
  // columns, 0.288 without, 0.187 for the paper's two passes).
  // `zero_is_hole` should be set when code 0 marks kept entries (it does in
  // the compression pipeline): without it the holes dominate the distances
  // (measured: 0.138 vs 0.080 with it; paper 0.101, spread counted without
  // holes).
  SketchSettings sketch;
  // Steps 2-4: candidate list length. 10 is the usual choice for 2-opt /
  // Or-opt on neighbour lists; more costs time linearly for little gain.
  std::size_t neighbours = 10;
  // Step 3: local search on/off, and its move budget in moves per patch
  // (a safety bound; typical runs use well under 1).
  bool improve_tour = true;
  std::size_t tour_moves_per_patch = 20;
  // Step 4: sweeps of the quad refinement (0 = keep the cut tour as it is;
  // it stops earlier when a sweep changes nothing) and the longest chain
  // move in quads (0 = swaps only).
  std::size_t quad_passes = 30;
  std::size_t quad_chain = 16;
};

struct OrderingReport {
  double seconds_sketch = 0.0;
  double seconds_neighbours = 0.0;
  double seconds_tour = 0.0;
  double seconds_quads = 0.0;
  std::size_t sketch_dims = 0;
  double sketch_captured = 1.0;  // fraction of centred row/column energy in the sketch
  double greedy_length = 0.0;    // open path lengths in sketch space
  double tour_length = 0.0;
  std::size_t two_opt_moves = 0;
  std::size_t or_opt_moves = 0;
  double quad_cost_before = 0.0;  // ordering_quads.h objective, sketch space
  double quad_cost_after = 0.0;
  std::size_t quad_swaps = 0;
  std::size_t quad_chains = 0;
  std::size_t quad_sweeps = 0;
};

// Our ordering; `report` (optional) receives timings and figures of each
// step. Deterministic for fixed settings and thread count. Returns the
// identity for n < 3 (nothing to gain).
Permutation our_ordering(const std::uint8_t* image, std::size_t n, std::size_t channels,
                         const OrderingSettings& settings, OrderingReport* report = nullptr);

}  // namespace bounce
