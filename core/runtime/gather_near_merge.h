#pragma once
// Building the final gather's rows (runtime/final_gather_build.h), second
// half: the near sources every chunk of points found become one list, placed
// on their surface; those too few rays landed in are dropped, their rays
// folded back into the rows; and every row names the merged sources.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "patches/surface_patch_lookup.h"
#include "raytrace/ray_tracer.h"
#include "runtime/final_gather.h"
#include "runtime/gather_chunk_rows.h"

namespace bounce {

// The near sources of every chunk as one list, numbered in chunk order (the
// same whatever the thread count): per chunk, each of its sources' number in
// the list; per source, the rays that landed in it, its sample, the sums of
// its landing points and albedo, and its first landing point.
struct MergedNearSources {
  std::vector<std::vector<std::uint32_t>> number;
  std::vector<std::uint32_t> count, sample;
  std::vector<glm::dvec3> position_sum, albedo_sum;
  std::vector<glm::vec3> first;
  std::size_t size() const { return count.size(); }
};

// Merges the chunks' near sources (one found by several chunks becomes one)
// and fills g.near: normals and patches from the merged list, albedo the
// mean over the rays that landed, and position where place_near_sources()
// puts each.
MergedNearSources merge_near_sources(const std::vector<ChunkRows>& chunks,
                                     const SurfacePatchLookup& lookup, FinalGather& g);

// Each near source is lit at the mean of its landing points unless the way
// there from its first landing point, `offset` above the surface, is
// blocked: then the mean lies under something standing on its triangle, and
// the source is lit at that first point. Thread-parallel.
void place_near_sources(const RayTracer& tracer, float offset, const MergedNearSources& merged,
                        FinalGather& g);

// What drop_rare_near_sources() gives a dropped source instead of a number.
constexpr std::uint32_t kDroppedNearSource = 0xFFFFFFFFu;

// Near sources fewer than `min_rays` rays landed in (over all points) are
// dropped from g.near (and their rays from g.rays_near): each costs a shadow
// ray every frame for a ray or two of light, noise at one point's 1 / rays.
// Returns each merged source's number among those kept, or
// kDroppedNearSource.
std::vector<std::uint32_t> drop_rare_near_sources(const MergedNearSources& merged, int min_rays,
                                                  FinalGather& g);

// Rewrites every chunk's rows to name kept near sources by their number
// after the patches, clusters and samples, and folds the rays of dropped
// ones into the row's entry for the surface they landed on (its sample, else
// its patch, else its cluster, else a new entry for its patch), counting
// them in `traced`'s seen rays where they join a patch or cluster entry.
void renumber_rows(TracedRows& traced, const MergedNearSources& merged,
                   const std::vector<std::uint32_t>& near_id, const GatherPlan& plan,
                   const SurfacePatchLookup& lookup, const FinalGather& g);

}  // namespace bounce
