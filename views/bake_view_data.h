#pragma once
// What the studio's views show: one bake folder (docs/bake-format.md) read
// back, plus the scene it was baked from when that is still on disk. The
// studio writes every bake it makes to a folder first and shows it from
// there, so a view shows exactly the data a user exports.
#include <filesystem>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "bounce/bake_folder.h"
#include "bounce/scene.h"

namespace bounce::views {

// One occupied voxel, a row of voxels.npy.
struct VoxelRow {
  glm::ivec3 cell;
  glm::vec3 centre;
  float surface_area = 0.0f;
  int samples = 0;
  int patches = 0;
};

struct BakeViewData {
  LoadedBake bake;                     // patches, samples, matrices, manifest
  std::shared_ptr<const Scene> scene;  // null when the scene file is gone
  std::vector<VoxelRow> voxels;        // voxels.npy
  float cell_size = 0.0f;              // manifest grid.cell_size
  std::vector<float> form_factors;     // F.npy (n x n, row = source), empty when absent
  // closure.npy: per patch, the share of its light that lands on sampled
  // surface, and the scale the balancing applied to its form-factor row;
  // empty for bakes without balancing.
  std::vector<float> closure;
  std::vector<float> row_scale;

  std::size_t patch_count() const { return bake.size(); }
};

// Reads `dir`; `scene`, when given, is the scene the bake was made from
// (otherwise the manifest's scene.path is loaded if it exists). Throws
// bounce::Error naming the file on any problem.
std::shared_ptr<const BakeViewData> load_bake_view_data(const std::filesystem::path& dir,
                                                        std::shared_ptr<const Scene> scene = {});

}  // namespace bounce::views
