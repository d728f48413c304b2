#pragma once
// Building the final gather's rows (runtime/final_gather_build.h), first
// half: every point traces its rays and chooses its entries, in chunks of
// points traced in parallel. Each chunk keeps its own rows and its own near
// sources, numbered within the chunk; gather_near_merge.h then merges the
// near sources over the chunks and joins the rows in point order, so the
// result does not depend on the thread count.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "base/progress.h"
#include "patches/surface_patch_lookup.h"
#include "raytrace/ray_tracer.h"
#include "runtime/final_gather.h"
#include "runtime/gather_spots.h"
#include "runtime/surface_cell_key.h"

namespace bounce {

struct FinalGatherSettings;

// What the settings come to for one build, in the units the rays use.
struct GatherPlan {
  std::size_t rays = 0, kept = 0, sample_kept = 0;
  double coverage = 0.0, sample_coverage = 0.0;
  bool sample_sources = false, near_sources = false, spot_sources = false;
  float near_distance = 0.0f;                // world units
  float near_cell = 0.0f, spot_cell = 0.0f;  // lattice cell edges, world units
  float offset = 0.0f;                       // ray origins lifted off the surface, world units
  std::uint64_t seed = 0;
  std::size_t patches = 0, sample_base = 0;  // sample_base: patches + clusters
};
GatherPlan plan_of(const FinalGatherSettings& settings, const VoxelGrid& grid,
                   const RayTracer& tracer, const FinalGather& g);

// The near sources one chunk of points found, numbered in order of first
// landing: sums of the landing points and their albedo, the first landing
// point and its side's normal.
struct ChunkNearSources {
  std::vector<SurfaceCellKey> keys;
  std::vector<glm::dvec3> position_sum, albedo_sum;
  std::vector<glm::vec3> first, normal;
  std::vector<std::uint32_t> count;
};

// Chunk rows name a near source by its chunk-local number with this bit set
// until the chunks are merged.
constexpr std::uint32_t kChunkNearSource = 0x80000000u;

// One chunk's rows: `count` entries per point, in point order.
struct ChunkRows {
  std::vector<std::uint32_t> source;
  std::vector<float> weight;
  std::vector<std::uint32_t> count;
  ChunkNearSources near;
};

// Where the rays went, summed over points (FinalGather::rays_landed...).
struct RayTally {
  std::size_t landed = 0, escaped = 0, back = 0, unrepresented = 0, near = 0, enclosed = 0;
  RayTally& operator+=(const RayTally& o);
};

// Over all points: the rows of each chunk, where the rays went, and what
// weighs the sources' light (FinalGather::seen_first): the rays read through
// a patch or cluster entry that landed on each sample, those folded into a
// cluster per patch, and the spot cells the far rays landed in.
struct TracedRows {
  std::vector<ChunkRows> chunks;
  RayTally tally;
  std::vector<std::uint64_t> seen_rays, cluster_rays;
  SpotCells spot_cells;
};

// Traces the rays of every point (`positions`, unit `normals`) and chooses
// each point's entries; `g` holds the clusters already. Thread-parallel,
// `progress` advanced per chunk.
TracedRows trace_rows(const RayTracer& tracer, const SurfacePatchLookup& lookup,
                      const std::vector<glm::vec3>& positions,
                      const std::vector<glm::vec3>& normals, const GatherPlan& plan,
                      const FinalGather& g, Progress* progress);

}  // namespace bounce
