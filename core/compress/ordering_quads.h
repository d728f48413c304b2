#pragma once
// Block-aware refinement. BC1 encodes each 4x4 block on its own, and a
// symmetric reordering makes the same groups of four ("quads": positions
// 4g..4g+3) the rows and the columns of every block. The block error hence
// depends on which patches share a quad, not on the order of the quads nor
// on the order inside one: a tour only serves as a start, and cutting it into
// fours puts unrelated patches together wherever a quad straddles a jump.
//
// This local search lowers
//   sum over quads of sum over members |s_i - mean of the quad|^2
// on the sketches s (the k-means objective with every cluster of size 4):
// the sketch distance stands for the row distance, and a row far from its
// quad's mean spreads every block of that block row. Two kinds of moves:
//   swap   patch a with a member of the quad of one of a's nearest
//          neighbours (any two quads);
//   chain  patch a leaves its quad g for quad g + L (L quads along the path,
//          either way), and each quad in between hands one member on towards
//          g. This repairs a run of quads cut at the wrong offset from the
//          tour (each holding halves of two clusters), which no single swap
//          improves. The best member to hand on at each step is found by
//          dynamic programming over the chain (4 x 4 choices per step).
// A change of quad q that takes out o and puts in i costs
//   (|i|^2 - |o|^2) - (2 S_q.(i - o) + |i - o|^2) / m_q
// (S_q: sum of the quad's sketches, m_q: its size), O(dims). Quad sizes never
// change, so the last, partial quad (n not a multiple of 4) stays partial.
#include <cstddef>

#include "compress/ordering_knn.h"
#include "compress/ordering_permutation.h"

namespace bounce {

struct QuadRefinement {
  double cost_before = 0.0;  // the objective above, on the input order
  double cost_after = 0.0;
  std::size_t swaps = 0;
  std::size_t chains = 0;
  std::size_t passes = 0;
};

// Sum over quads of the squared distances of their members to the quad mean.
double quad_cost(const float* points, std::size_t dims, const Permutation& order);

// Improves `order` in place; up to max_passes sweeps over all patches (stops
// earlier when a sweep finds nothing); chains span at most max_chain quads
// (0: swaps only). Cost per sweep O(n (k + max_chain) dims). Deterministic.
QuadRefinement refine_quads(const float* points, std::size_t dims, const NeighbourLists& nn,
                            Permutation& order, std::size_t max_passes, std::size_t max_chain = 16);

}  // namespace bounce
