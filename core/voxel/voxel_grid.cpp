#include "voxel/voxel_grid.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace bounce {

VoxelGrid::VoxelGrid(const Bounds& scene_bounds, int resolution) : resolution_(resolution) {
  if (resolution < 1 || resolution > kMaxResolution)
    throw SettingsError("voxel_resolution", "voxel resolution must be between 1 and " +
                                                std::to_string(kMaxResolution) + ", got " +
                                                std::to_string(resolution));
  if (scene_bounds.empty()) throw SettingsError("voxel grid", "the scene has no geometry");
  const glm::vec3 extent = scene_bounds.extent();
  const float longest = std::max({extent.x, extent.y, extent.z});
  if (!(longest > 0.0f) || !std::isfinite(longest))
    throw SettingsError("voxel grid", "the scene's bounds are degenerate (a single point?)");
  // Pad by a small fraction of a cell so boundary surfaces sit inside cells.
  const float pad = 1e-3f * longest / static_cast<float>(resolution);
  cell_ = (longest + 2.0f * pad) / static_cast<float>(resolution);
  // Shorter axes: enough cells to hold the surface with a margin, not the
  // full padding (which would add a whole layer of cells for a few ulps).
  for (int a = 0; a < 3; ++a) {
    dims_[a] = std::max(1, static_cast<int>(std::ceil(extent[a] / cell_)));
    if (static_cast<float>(dims_[a]) * cell_ - extent[a] < 1e-4f * cell_) dims_[a]++;
  }
  // Centre the grid on the padded bounds along the shorter axes.
  const glm::vec3 size = glm::vec3(dims_) * cell_;
  const glm::vec3 center = scene_bounds.center();
  bounds_.lo = center - 0.5f * size;
  bounds_.hi = center + 0.5f * size;
}

VoxelGrid VoxelGrid::restore(const glm::vec3& origin, float cell_size, const glm::ivec3& dims) {
  if (!(cell_size > 0.0f) || !std::isfinite(cell_size) || !std::isfinite(origin.x) ||
      !std::isfinite(origin.y) || !std::isfinite(origin.z))
    throw SettingsError("voxel grid",
                        "the grid's origin and cell size must be finite, the cell "
                        "size positive");
  for (int a = 0; a < 3; ++a)
    if (dims[a] < 1 || dims[a] > kMaxResolution)
      throw SettingsError("voxel grid", "the grid's cell counts must be between 1 and " +
                                            std::to_string(kMaxResolution));
  VoxelGrid g;
  g.cell_ = cell_size;
  g.dims_ = dims;
  g.resolution_ = std::max({dims.x, dims.y, dims.z});
  g.bounds_.lo = origin;
  g.bounds_.hi = origin + glm::vec3(dims) * cell_size;
  return g;
}

glm::ivec3 VoxelGrid::coord_of(std::uint64_t linear) const {
  const auto dx = static_cast<std::uint64_t>(dims_.x), dy = static_cast<std::uint64_t>(dims_.y);
  return {static_cast<int>(linear % dx), static_cast<int>((linear / dx) % dy),
          static_cast<int>(linear / (dx * dy))};
}

glm::ivec3 VoxelGrid::cell_of(const glm::vec3& p) const {
  glm::ivec3 c;
  for (int a = 0; a < 3; ++a) {
    const int i = static_cast<int>(std::floor((p[a] - bounds_.lo[a]) / cell_));
    c[a] = std::clamp(i, 0, dims_[a] - 1);
  }
  return c;
}

Bounds VoxelGrid::cell_bounds(const glm::ivec3& c) const {
  Bounds b;
  b.lo = bounds_.lo + glm::vec3(c) * cell_;
  b.hi = b.lo + glm::vec3(cell_);
  return b;
}

}  // namespace bounce
