#pragma once
// The final gather's spots (runtime/final_gather.h): the cells of each
// sample the far gather rays landed in most, lit every frame so that a
// sample's light is that of the parts of it the points see.
#include <cstdint>
#include <utility>
#include <vector>

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

// The spot cells, grouped by sample. Every far ray adds to one, and a
// sample, a quarter of a voxel across, holds a handful of cells an eighth of
// a voxel across (a few per triangle crossing it), so a short scan of its own
// finds a cell: a hash map of every cell, one node per cell, made Sponza's
// final gather (37M far rays at 4096 patches) take half as long again as
// without spots.
class SpotCells {
 public:
  // Adds `cell`'s rays to the cell `key` names, which keeps the earlier first
  // ray of the two: the result does not depend on the order cells are added in.
  void add(const SurfaceCellKey& key, const SpotCell& cell);
  // Adds every cell of `other`.
  void merge(const SpotCells& other);
  std::size_t size() const { return size_; }
  // f(key, cell) for every cell, by sample.
  template <class F>
  void for_each(F&& f) const {
    for (const auto& cells : by_sample_)
      for (const auto& [key, cell] : cells) f(key, cell);
  }

 private:
  std::vector<std::vector<std::pair<SurfaceCellKey, SpotCell>>> by_sample_;
  std::size_t size_ = 0;
};

// Each sample's `spots` cells with the most far rays (ties by first ray)
// become its spots, weighted by their rays: FinalGather::spot_first, and
// the spots appended to the near sources, lit with the sample's albedo.
void make_spots(const SurfacePatchLookup& lookup, const SpotCells& cells, int spots,
                FinalGather& g);

}  // namespace bounce
