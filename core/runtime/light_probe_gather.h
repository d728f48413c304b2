#pragma once
// The bake-time gather of light probes (runtime/light_probes.h) at given
// positions: each probe's kProbeDirections directions are final-gather
// points with the vertices' rays and seed and no near sources or spots (a
// placed probe stands half a voxel or more from every surface, twice the
// near sources' reach).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "base/progress.h"
#include "patches/patch_set.h"
#include "patches/surface_patch_lookup.h"
#include "raytrace/ray_tracer.h"
#include "runtime/light_probes.h"
#include "voxel/voxel_grid.h"

namespace bounce {

// `rays` per direction; `seed` the bake's. Thread-parallel; the result does
// not depend on the thread count.
LightProbes gather_light_probes(const RayTracer& tracer, const SurfacePatchLookup& lookup,
                                const std::vector<Patch>& patches, const VoxelGrid& grid,
                                std::vector<glm::vec3> positions, int rays, std::uint64_t seed,
                                Progress* progress = nullptr);

}  // namespace bounce
