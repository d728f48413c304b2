#include "partial_view_data.h"

namespace bounce::views {

namespace {

nlohmann::json vec3(const glm::vec3& v) { return {v.x, v.y, v.z}; }

nlohmann::json partial_manifest(const Scene& scene, const VoxelGrid& grid) {
  nlohmann::json lights = nlohmann::json::array();
  for (const Light& l : scene.lights) lights.push_back({{"name", l.name}});
  return {{"partial", true},
          {"scene", {{"name", scene.name}, {"path", scene.path}, {"lights", lights}}},
          {"grid",
           {{"origin", vec3(grid.bounds().lo)},
            {"cell_size", grid.cell_size()},
            {"dims", {grid.dims().x, grid.dims().y, grid.dims().z}}}}};
}

// voxels.npy's rows as the writer makes them, counting what exists so far.
std::vector<VoxelRow> voxel_rows(const BakeResult& r) {
  const std::size_t n = r.voxels.voxels.size();
  std::vector<int> patches(n, 0);
  for (const Patch& p : r.patches.patches)
    if (p.voxel < n) ++patches[p.voxel];
  const bool sampled = r.samples.first.size() == n + 1;
  std::vector<VoxelRow> rows;
  rows.reserve(n);
  for (std::size_t v = 0; v < n; ++v) {
    const OccupiedVoxel& ov = r.voxels.voxels[v];
    const int samples = sampled ? static_cast<int>(r.samples.first[v + 1] - r.samples.first[v]) : 0;
    rows.push_back(
        {ov.coord, r.voxels.grid.cell_bounds(ov.coord).center(), ov.area, samples, patches[v]});
  }
  return rows;
}

}  // namespace

std::shared_ptr<const BakeViewData> partial_view_data(std::shared_ptr<const Scene> scene,
                                                      const BakeResult& partial) {
  auto data = std::make_shared<BakeViewData>();
  data->bake.manifest = partial_manifest(*scene, partial.voxels.grid);
  data->cell_size = partial.voxels.grid.cell_size();
  data->voxels = voxel_rows(partial);
  if (!partial.patches.patches.empty()) {
    data->bake.patches = partial.patches;
    data->bake.samples = partial.samples;
    data->bake.patch_of_sample = partial.patch_of_sample;
  }
  data->scene = std::move(scene);
  return data;
}

}  // namespace bounce::views
