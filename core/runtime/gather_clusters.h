#pragma once
// The final gather's clusters (runtime/final_gather.h): where a point's weak
// patches are folded, and how a cluster's light is shared among its patches.
#include <cstdint>
#include <vector>

#include "patches/patch_set.h"
#include "patches/surface_patch_lookup.h"
#include "runtime/final_gather.h"
#include "voxel/voxel_grid.h"

namespace bounce {

// Clusters: the patches of one block of `block` x `block` x `block` voxels
// whose normals share a dominant axis direction (a floor and the wall
// standing on it stay apart) and whose positions along that axis lie in one
// quarter-voxel layer (a floor and the lit top of a slab standing on it stay
// apart too: a point under the slab sees the floor, not the slab's top),
// numbered in order of first appearance. Fills g.cluster_of_patch,
// g.cluster_share (by area) and g.clusters.
void make_clusters(const std::vector<Patch>& patches, const VoxelGrid& grid, int block,
                   FinalGather& g);

// The seen weights (FinalGather::seen_first) from the rays read through
// patch and cluster entries: `seen` per sample, the rays that landed on it;
// `cluster_rays` per patch, the rays folded into its cluster. Each patch's
// samples are weighed by the rays that landed on them, each patch's share of
// its cluster by the rays folded into it. A patch or cluster no such ray
// landed on keeps its area weights.
void weigh_by_seen_rays(const SurfacePatchLookup& lookup, const std::vector<std::uint64_t>& seen,
                        const std::vector<std::uint64_t>& cluster_rays, FinalGather& g);

}  // namespace bounce
