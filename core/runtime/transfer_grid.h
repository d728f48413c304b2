#pragma once
// Which voxel a surface point falls in, for the light transfer from patches
// to the mesh. Its own file so that the bake readers (and their fuzz targets)
// can read a manifest's grid without the ray tracer the transfer needs.
#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include "voxel/voxel_grid.h"

namespace bounce {

// The bake's voxel grid, as much of it as the transfer needs: cells are cubes,
// cell (i, j, k) spans origin + cell_size * [i, i+1] x [j, j+1] x [k, k+1].
struct TransferGrid {
  glm::vec3 origin{0.0f};
  float cell_size = 1.0f;
  glm::ivec3 dims{1};

  static TransferGrid from(const VoxelGrid& grid);
  // From a bake manifest's "grid" block (docs/bake-format.md); throws
  // bounce::Error when it is missing or malformed.
  static TransferGrid from_manifest(const nlohmann::json& manifest);

  glm::ivec3 cell_of(const glm::vec3& p) const;
};

}  // namespace bounce
