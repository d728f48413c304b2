#include "report/report_probes.h"

#include <array>

#include "reference/reference_cache.h"
#include "runtime/light_probe_placement.h"
#include "runtime/light_probes.h"
#include "runtime/probe_interpolation.h"
#include "runtime/transfer_grid.h"
#include "voxel/voxelization.h"

namespace bounce {

ReportProbes::ReportProbes(const RayTracer& tracer, const ReferencePathTracer& reference,
                           int eval_grid, const ReferenceCache* cache, Progress* progress)
    : tracer_(tracer) {
  const Scene& scene = tracer.scene();
  const Voxelization voxels = voxelize(scene, VoxelGrid(scene.bounds(), eval_grid), progress);
  ProbePlacementRequest request;
  request.max_probes = voxels.grid.cell_count();
  request.max_setting = "eval_grid";
  const ProbePlacement placed = place_light_probes(tracer, voxels, request, progress);
  for (const std::size_t p : probe_reference_choice(placed.position.size(), kReportProbePoints))
    positions_.push_back(placed.position[p]);
  points_ = probe_reference_points(positions_);
  reference_ = cached_reference_points(reference, points_, cache, progress);
}

ProbeReferenceError ReportProbes::measure(const BakeResult& bake,
                                          const std::vector<glm::vec3>& reflected,
                                          const std::vector<glm::vec3>& sample_light) const {
  // A grid too coarse for any probe lights nothing that moves: all zero,
  // relative RMSE 1 and level 0.
  if (bake.light_probes.size() == 0)
    return compare_probe_sh(points_, reference_,
                            std::vector<glm::vec3>(positions_.size() * kShCoefficients));
  std::vector<glm::vec3> direction_irradiance, probe_sh;
  bake.light_probes.gather.irradiance(reflected, sample_light, direction_irradiance);
  fit_probe_sh(direction_irradiance, probe_sh);
  const ProbeInterpolator blend(bake.light_probes.position, TransferGrid::from(bake.voxels.grid),
                                tracer_, bake.light_probes.volumes);
  std::vector<glm::vec3> sh;
  sh.reserve(positions_.size() * kShCoefficients);
  std::array<glm::vec3, kShCoefficients> at{};
  for (const glm::vec3& p : positions_) {
    blend.sh_at(p, probe_sh, at);
    sh.insert(sh.end(), at.begin(), at.end());
  }
  return compare_probe_sh(points_, reference_, sh);
}

}  // namespace bounce
