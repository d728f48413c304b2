#include "compress/ordering.h"

#include <chrono>
#include <limits>

#include "base/error.h"
#include "compress/ordering_knn.h"
#include "compress/ordering_quads.h"
#include "compress/ordering_tour.h"

namespace bounce {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

Permutation our_ordering(const std::uint8_t* image, std::size_t n, std::size_t channels,
                         const OrderingSettings& settings, OrderingReport* report) {
  if (channels == 0) throw Error("ordering", "our_ordering: no channels");
  OrderingReport local;
  OrderingReport& r = report ? *report : local;
  r = OrderingReport{};
  if (n < 3) return identity_permutation(n);

  auto clock = std::chrono::steady_clock::now();
  const Sketch sketch = principal_sketch(image, n, channels, settings.sketch);
  const float* x = sketch.coords.data();
  const std::size_t dims = sketch.dims;
  r.sketch_dims = dims;
  r.sketch_captured = sketch.captured;
  r.seconds_sketch = seconds_since(clock);

  clock = std::chrono::steady_clock::now();
  const NeighbourLists nn = nearest_neighbours(x, n, dims, settings.neighbours);
  r.seconds_neighbours = seconds_since(clock);

  clock = std::chrono::steady_clock::now();
  // Start at an end of the principal axis: a path that starts in the middle
  // of the data has to come back across it.
  std::uint32_t start = 0;
  for (std::size_t i = 1; i < n; ++i)
    if (x[i * dims] < x[std::size_t{start} * dims]) start = static_cast<std::uint32_t>(i);
  Permutation order = greedy_sketch_tour(x, n, dims, nn, start);
  r.greedy_length = tour_length(x, dims, order, false);
  if (settings.improve_tour) {
    const TourImprovement t =
        improve_tour(x, n, dims, nn, order, settings.tour_moves_per_patch * n);
    r.two_opt_moves = t.two_opt_moves;
    r.or_opt_moves = t.or_opt_moves;
  }
  cut_at_longest_edge(x, dims, order);
  r.tour_length = tour_length(x, dims, order, false);
  r.seconds_tour = seconds_since(clock);

  clock = std::chrono::steady_clock::now();
  const QuadRefinement q =
      refine_quads(x, dims, nn, order, settings.quad_passes, settings.quad_chain);
  r.quad_cost_before = q.cost_before;
  r.quad_cost_after = q.cost_after;
  r.quad_swaps = q.swaps;
  r.quad_chains = q.chains;
  r.quad_sweeps = q.passes;
  r.seconds_quads = seconds_since(clock);
  return order;
}

}  // namespace bounce
