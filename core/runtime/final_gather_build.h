#pragma once
// Building a final gather's rows at bake time (the data they make, and the
// work per frame, are runtime/final_gather.h). The steps, each its own file:
//
//   1. clusters of the patches (gather_clusters.h);
//   2. every point's rays traced and its entries chosen, in chunks of points
//      (gather_chunk_rows.h);
//   3. the chunks' near sources merged, placed, the rare ones dropped and the
//      rows renumbered (gather_near_merge.h);
//   4. each sample's spots from where the far rays landed (gather_spots.h);
//   5. the rows joined, the seen weights from the rays read through patch and
//      cluster entries (gather_clusters.h), the compact rows packed.
#include <vector>

#include <glm/glm.hpp>

#include "base/progress.h"
#include "patches/patch_set.h"
#include "patches/surface_patch_lookup.h"
#include "raytrace/ray_tracer.h"
#include "runtime/final_gather.h"
#include "runtime/final_gather_settings.h"
#include "voxel/voxel_grid.h"

namespace bounce {

// Gathers for points `positions` with unit normals `normals` (the side that
// receives). Thread-parallel; the result does not depend on the thread count.
// `patches`: the bake's (positions, normals and areas make the clusters);
// `grid`: its voxel grid.
FinalGather build_final_gather(const RayTracer& tracer, const SurfacePatchLookup& lookup,
                               const std::vector<Patch>& patches, const VoxelGrid& grid,
                               const std::vector<glm::vec3>& positions,
                               const std::vector<glm::vec3>& normals,
                               const FinalGatherSettings& settings, Progress* progress = nullptr);

}  // namespace bounce
