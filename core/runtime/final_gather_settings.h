#pragma once
// How the final gather's rows are built (runtime/final_gather_build.h). The
// defaults written here are the bake's: the settings table's rows
// final_gather_rays, final_gather_near, final_gather_near_min_rays and
// final_gather_spots take theirs from this struct (settings/bake_settings.h), and
// their ranges are the table's alone. The other fields are the method's own
// constants, not settings a bake offers.
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace bounce {

struct FinalGatherSettings {
  int rays = 256;  // per point
  // Patches kept exactly per point: the strongest, until they hold
  // `coverage` of the point's landed rays, at most `kept`.
  int kept = 64;
  double coverage = 0.9;
  // Samples kept exactly per point before the patches: the strongest, until
  // they hold `sample_coverage` of the landed rays, at most `sample_kept`
  // per 256 rays (0: patches only). The cap grows with the rays because the
  // samples a point's rays reach do: a fixed cap would hand a growing share
  // of the rays back to patch means as rays are added, and a patch mean
  // weighs its surface by area where the point weighs it by how it sees it
  // (the empty Cornell box's walls lost 1% more light at 2048 rays with the
  // cap fixed at 64 than at 256 rays).
  int sample_kept = 128;
  double sample_coverage = 0.5;
  // The cap on sample entries per point at `rays` rays.
  std::size_t sample_cap() const {
    if (sample_kept <= 0 || rays <= 0) return 0;
    return static_cast<std::size_t>(
        std::ceil(static_cast<double>(sample_kept) * static_cast<double>(rays) / 256.0));
  }
  // Near sources: rays landing closer than `near` voxels to their point
  // (0: none) read a near source, a cell 1 / `near_resolution` of a voxel
  // across on the surface they hit.
  float near = 0.25f;
  int near_resolution = 24;
  // Near sources fewer rays than this landed in, over all points, go back to
  // the sample (or patch, or cluster) the points read for that surface.
  int near_min_rays = 2;
  // Spots per sample (0: samples are lit at their centres) and the cells
  // per voxel edge the far rays' landing points are grouped by.
  int spots = 2;
  int spot_resolution = 8;
  // Cluster blocks are this many voxels along each axis.
  int cluster_voxels = 4;
  std::uint64_t seed = 1;
  // Ray origins are lifted off the surface by this many RayTracer::epsilon().
  float offset_epsilons = 10.0f;
};

}  // namespace bounce
