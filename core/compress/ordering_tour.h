#pragma once
// A short tour through patch sketches (Euclidean distance): a greedy
// nearest-neighbour seed, improved by 2-opt and Or-opt moves restricted to
// candidate lists (Johnson & McGeoch's neighbour-list local search with
// don't-look bits), then cut open at its longest edge. Consecutive patches of
// the resulting path have similar rows, which is what the symmetric
// reordering needs; ordering_quads.h then optimises the grouping into fours.
#include <cstddef>
#include <cstdint>

#include "compress/ordering_knn.h"
#include "compress/ordering_permutation.h"

namespace bounce {

// Length of the open path (cycle = false) or closed tour through `order`.
double tour_length(const float* points, std::size_t dims, const Permutation& order, bool cycle);

// Greedy nearest-neighbour path from `start`: the next point is the nearest
// unvisited one, taken from the candidate list when it still has an
// unvisited entry, otherwise found by a scan of all unvisited points
// (ties to the smaller index). O(n k) plus O(n dims) per scan; the scans are
// needed only where the path has exhausted a neighbourhood.
Permutation greedy_sketch_tour(const float* points, std::size_t n, std::size_t dims,
                               const NeighbourLists& nn, std::uint32_t start);

struct TourImprovement {
  std::size_t two_opt_moves = 0;
  std::size_t or_opt_moves = 0;
  bool hit_move_limit = false;
};

// 2-opt and Or-opt (segments of 1-3 points moved, either way round) on the
// closed tour `order`, trying only new edges to candidate neighbours; every
// move shortens the tour. Array representation: a move reverses the shorter
// side, O(n) at worst. Stops when no candidate move improves or after
// max_moves moves. Deterministic.
TourImprovement improve_tour(const float* points, std::size_t n, std::size_t dims,
                             const NeighbourLists& nn, Permutation& order, std::size_t max_moves);

// Rotates the closed tour so that it starts just after its longest edge:
// the open path drops that edge (ties to the first such edge).
void cut_at_longest_edge(const float* points, std::size_t dims, Permutation& order);

}  // namespace bounce
