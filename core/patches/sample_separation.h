#pragma once
// Which samples of one voxel stand on either side of a surface that lies
// between them: the floor on the two sides of a wall thinner than a voxel,
// or the ground on either side of a small solid box. One patch made of both
// would average the light of two places that do not see each other, and
// every point gathering from it on the dark side would get the lit side's
// light (docs/method.md section 4).
//
// Two samples of one surface (facing the same way within 26 degrees, each
// near the other's plane) are separated when the segment between them,
// lifted off the surface by 0.15 of their distance, is blocked: something
// stands on the surface between them. The lift keeps the segment clear of
// the surface's own bulge at a crease or curve; samples facing further apart are left to
// the clustering's metric, which a test here would split at every convex
// edge (the lifted segment between a box's top and side crosses the box).
//
// Only voxels holding samples that face opposite ways are tested: a thin
// wall or a small solid has both its faces in the voxel, and every other
// voxel costs no rays.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "patches/samples.h"
#include "raytrace/ray_tracer.h"

namespace bounce {

class SampleSeparation {
 public:
  // The voxel's samples are set.first[voxel] .. set.first[voxel + 1]; local
  // index i is sample set.first[voxel] + i.
  SampleSeparation(const RayTracer& tracer, const SampleSet& set, std::size_t voxel);

  // No pair is separated (most voxels): the clustering needs no bit sets.
  bool empty() const { return separated_pairs_ == 0; }
  std::size_t words() const { return words_; }
  // Bit j of row i is set when local samples i and j are separated.
  const std::uint64_t* row(std::size_t i) const { return bits_.data() + i * words_; }
  std::size_t separated_pairs() const { return separated_pairs_; }
  std::size_t rays() const { return rays_; }

 private:
  std::size_t words_ = 0;
  std::vector<std::uint64_t> bits_;
  std::size_t separated_pairs_ = 0;
  std::size_t rays_ = 0;
};

}  // namespace bounce
