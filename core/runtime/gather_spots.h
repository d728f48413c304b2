#pragma once
// The final gather's spots (runtime/final_gather.h): the cells of each
// sample the far gather rays landed in most, lit every frame so that a
// sample's light is that of the parts of it the points see.
#include <cstdint>
#include <unordered_map>

#include <glm/glm.hpp>

#include "patches/surface_patch_lookup.h"
#include "runtime/final_gather.h"
#include "runtime/surface_cell_key.h"

namespace bounce {

// A spot's cell as the far rays found it: how many landed in it, and the
// first of them (in point and ray order, so that the spot is the same
// whatever the thread count): where it landed and the side it landed on.
struct SpotCell {
  std::uint64_t rays = 0, first = 0;
  glm::vec3 position{0.0f}, normal{0.0f};
};
using SpotCells = std::unordered_map<SurfaceCellKey, SpotCell, SurfaceCellKeyHash>;

// Adds `cell`'s rays to the cell `key` names, which keeps the earlier first
// ray of the two: the result does not depend on the order cells are added in.
void add_to_spot_cell(SpotCells& cells, const SurfaceCellKey& key, const SpotCell& cell);

// Each sample's `spots` cells with the most far rays (ties by first ray)
// become its spots, weighted by their rays: FinalGather::spot_first, and
// the spots appended to the near sources, lit with the sample's albedo.
void make_spots(const SurfacePatchLookup& lookup, const SpotCells& cells, int spots,
                FinalGather& g);

}  // namespace bounce
