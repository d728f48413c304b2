#include "runtime/light_probe_placement.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "base/error.h"

namespace bounce {

namespace {

// Empty cells sharing a face with an occupied one, in increasing linear
// index, without duplicates.
std::vector<std::uint64_t> candidate_cells(const Voxelization& voxels) {
  const glm::ivec3 dims = voxels.grid.dims();
  std::vector<std::uint64_t> cells;
  cells.reserve(6 * voxels.voxels.size());
  for (const OccupiedVoxel& v : voxels.voxels)
    for (int axis = 0; axis < 3; ++axis)
      for (const int step : {-1, 1}) {
        glm::ivec3 c = v.coord;
        c[axis] += step;
        if (c[axis] < 0 || c[axis] >= dims[axis] || voxels.find(c) >= 0) continue;
        cells.push_back(voxels.grid.linear_index(c));
      }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  return cells;
}

std::vector<glm::vec3> sphere_directions(int n) {
  std::vector<glm::vec3> d(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = 2.0 * std::numbers::pi * i / std::numbers::phi;
    d[static_cast<std::size_t>(i)] =
        glm::vec3(static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
                  static_cast<float>(z));
  }
  return d;
}

enum class Verdict : std::uint8_t { kKept, kEnclosed, kSeesNothing };

Verdict judge(const RayTracer& tracer, const glm::vec3& centre,
              const std::vector<glm::vec3>& directions) {
  const Scene& scene = tracer.scene();
  std::size_t backs = 0, fronts = 0;
  for (const glm::vec3& dir : directions) {
    const Hit h = tracer.intersect(centre, dir);
    if (!h.hit) continue;
    if (glm::dot(dir, h.geometric_normal) > 0.0f && !scene.two_sided(h.triangle))
      ++backs;
    else
      ++fronts;
  }
  if (2 * backs > directions.size()) return Verdict::kEnclosed;
  return fronts == 0 ? Verdict::kSeesNothing : Verdict::kKept;
}

}  // namespace

ProbePlacement place_light_probes(const RayTracer& tracer, const Voxelization& voxels,
                                  std::size_t max_probes, const char* max_setting,
                                  Progress* progress) {
  const std::vector<std::uint64_t> cells = candidate_cells(voxels);
  if (cells.size() > max_probes)
    throw Error(std::string("setting '") + max_setting + "'",
                "the grid has " + std::to_string(cells.size()) +
                    " empty cells next to surfaces, each a light probe, more than the " +
                    std::to_string(max_probes) + " allowed: raise it, or bake on a coarser grid");
  if (progress) progress->begin_stage("light probe placement", cells.size());
  const std::vector<glm::vec3> directions = sphere_directions(kProbeTestRays);
  std::vector<Verdict> verdict(cells.size());
#pragma omp parallel for schedule(dynamic, 64)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(cells.size()); ++i) {
    const auto k = static_cast<std::size_t>(i);
    const Bounds box = voxels.grid.cell_bounds(voxels.grid.coord_of(cells[k]));
    verdict[k] = judge(tracer, 0.5f * (box.lo + box.hi), directions);
  }
  ProbePlacement placement;
  placement.candidates = cells.size();
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (verdict[k] == Verdict::kEnclosed) {
      ++placement.rejected_enclosed;
    } else if (verdict[k] == Verdict::kSeesNothing) {
      ++placement.rejected_sees_nothing;
    } else {
      const Bounds box = voxels.grid.cell_bounds(voxels.grid.coord_of(cells[k]));
      placement.position.push_back(0.5f * (box.lo + box.hi));
    }
  }
  if (progress) {
    progress->advance(cells.size());
    progress->end_stage();
  }
  return placement;
}

}  // namespace bounce
