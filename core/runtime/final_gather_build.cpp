#include "runtime/final_gather_build.h"

#include <cmath>
#include <string>

#include "base/error.h"
#include "runtime/gather_chunk_rows.h"
#include "runtime/gather_clusters.h"
#include "runtime/gather_near_merge.h"
#include "runtime/gather_spots.h"

namespace bounce {

namespace {

// What the build itself needs of its inputs. The bake's own settings are
// range-checked by the settings table before they get here; these are the
// values without which the rows cannot be built at all.
void check_build_inputs(const std::vector<glm::vec3>& positions,
                        const std::vector<glm::vec3>& normals, const FinalGatherSettings& s) {
  if (positions.size() != normals.size())
    throw Error("final gather", "positions and normals differ in count");
  if (s.rays < 1 || s.kept < 1 || s.cluster_voxels < 1)
    throw Error("final gather", "rays, kept patches and cluster size per point must be at least 1");
  if (s.sample_kept < 0 || !(s.sample_coverage >= 0.0 && s.sample_coverage <= 1.0))
    throw Error("final gather", "kept samples must be >= 0 and their coverage in [0, 1]");
  if (s.spots < 0 || !(s.near >= 0.0f && std::isfinite(s.near)))
    throw Error("final gather", "spots per sample and the near distance must be at least 0");
  if (s.near_resolution < 1 || s.near_resolution > 1024 || s.spot_resolution < 1 ||
      s.spot_resolution > 1024)
    throw Error("final gather",
                "the near sources' and spots' resolutions must be in [1, 1024] per voxel");
}

void record_tally(const RayTally& t, FinalGather& g) {
  g.rays_landed = t.landed;
  g.rays_escaped = t.escaped;
  g.rays_back = t.back;
  g.rays_unrepresented = t.unrepresented;
  g.rays_near = t.near;
  g.points_enclosed = t.enclosed;
}

// The chunks' rows joined in point order.
void join_rows(const std::vector<ChunkRows>& chunks, std::size_t points, FinalGather& g) {
  g.first.reserve(points + 1);
  g.first.push_back(0);
  for (const ChunkRows& c : chunks) {
    for (std::uint32_t k : c.count) g.first.push_back(g.first.back() + k);
    g.source.insert(g.source.end(), c.source.begin(), c.source.end());
    g.weight.insert(g.weight.end(), c.weight.begin(), c.weight.end());
  }
}

}  // namespace

FinalGather build_final_gather(const RayTracer& tracer, const SurfacePatchLookup& lookup,
                               const std::vector<Patch>& patches, const VoxelGrid& grid,
                               const std::vector<glm::vec3>& positions,
                               const std::vector<glm::vec3>& normals,
                               const FinalGatherSettings& settings, Progress* progress) {
  check_build_inputs(positions, normals, settings);
  FinalGather g;
  g.patches = patches.size();
  g.rays = settings.rays;
  make_clusters(patches, grid, settings.cluster_voxels, g);
  const GatherPlan plan = plan_of(settings, grid, tracer, g);
  if (plan.sample_sources || plan.near_sources) g.samples = lookup.sample_count();
  TracedRows traced = trace_rows(tracer, lookup, positions, normals, plan, g, progress);
  record_tally(traced.tally, g);
  const MergedNearSources merged = merge_near_sources(traced.chunks, lookup, g);
  place_near_sources(tracer, plan.offset, merged, g);
  const std::vector<std::uint32_t> near_id =
      drop_rare_near_sources(merged, settings.near_min_rays, g);
  renumber_rows(traced, merged, near_id, plan, lookup, g);
  // The spots go after the near sources the rows read.
  if (plan.spot_sources) make_spots(lookup, traced.spot_cells, settings.spots, g);
  join_rows(traced.chunks, positions.size(), g);
  if (!traced.seen_rays.empty())
    weigh_by_seen_rays(lookup, traced.seen_rays, traced.cluster_rays, g);
  g.compact_rows();
  return g;
}

}  // namespace bounce
