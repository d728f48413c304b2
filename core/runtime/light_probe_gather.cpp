#include "runtime/light_probe_gather.h"

#include <utility>

#include "runtime/final_gather_build.h"
#include "runtime/final_gather_settings.h"

namespace bounce {

LightProbes gather_light_probes(const RayTracer& tracer, const SurfacePatchLookup& lookup,
                                const std::vector<Patch>& patches, const VoxelGrid& grid,
                                std::vector<glm::vec3> positions, int rays, std::uint64_t seed,
                                Progress* progress) {
  LightProbes probes;
  probes.position = std::move(positions);
  std::vector<glm::vec3> points, normals;
  points.reserve(probes.size() * kProbeDirections);
  normals.reserve(points.capacity());
  for (const glm::vec3& p : probes.position)
    for (const glm::vec3& d : probe_directions()) {
      points.push_back(p);
      normals.push_back(d);
    }
  FinalGatherSettings fg;
  fg.rays = rays;
  fg.near = 0.0f;
  fg.spots = 0;
  fg.seed = seed;
  probes.gather = build_final_gather(tracer, lookup, patches, grid, points, normals, fg, progress);
  return probes;
}

}  // namespace bounce
