#include "bake_view_data.h"

#include <cmath>

#include "bounce/bake_folder.h"
#include "bounce/scene.h"

namespace bounce::views {

namespace fs = std::filesystem;

namespace {

void require_shape(const fs::path& file, const std::vector<std::size_t>& shape,
                   std::size_t columns) {
  if (shape.size() != 2 || shape[1] != columns)
    throw Error(file.string(), "expected a 2-D array with " + std::to_string(columns) +
                                   " columns (docs/bake-format.md)");
}

// A whole-number column of voxels.npy (cell coordinates, sample and patch
// counts) as an int: converting a NaN or an out-of-range float is undefined,
// and the folder may come from anywhere.
int int_column(const fs::path& file, std::size_t row, std::size_t column, float v) {
  if (!(v >= -2147483648.0f && v < 2147483648.0f && v == std::floor(v)))
    throw Error(file.string(), "row " + std::to_string(row) + ", column " + std::to_string(column) +
                                   " holds " + std::to_string(v) + ", not a whole number");
  return static_cast<int>(v);
}

}  // namespace

std::shared_ptr<const BakeViewData> load_bake_view_data(const fs::path& dir,
                                                        std::shared_ptr<const Scene> scene) {
  auto data = std::make_shared<BakeViewData>();
  data->bake = BakeReader::read(dir, true);
  data->cell_size = data->bake.description.grid.cell_size;

  namespace vc = voxel_column;
  const fs::path voxel_file = dir / bake_file::kVoxels;
  const NpyArray<float> v = read_npy_f32(voxel_file);
  require_shape(voxel_file, v.shape, vc::kCount);
  data->voxels.reserve(v.shape[0]);
  for (std::size_t k = 0; k < v.shape[0]; ++k) {
    const float* r = &v.data[k * vc::kCount];
    const auto whole = [&](std::size_t c) { return int_column(voxel_file, k, c, r[c]); };
    const std::size_t cell = vc::kCell, centre = vc::kCentre;
    data->voxels.push_back({glm::ivec3(whole(cell), whole(cell + 1), whole(cell + 2)),
                            glm::vec3(r[centre], r[centre + 1], r[centre + 2]), r[vc::kArea],
                            whole(vc::kSamples), whole(vc::kPatches)});
  }

  if (auto f = read_form_factors(dir, data->patch_count())) data->form_factors = std::move(*f);

  const fs::path closure_file = dir / bake_file::kClosure;
  if (fs::exists(closure_file)) {
    const NpyArray<float> c = read_npy_f32(closure_file);
    require_shape(closure_file, c.shape, closure_column::kCount);
    if (c.shape[0] != data->patch_count())
      throw Error(closure_file.string(), "expected one row per patch (" +
                                             std::to_string(data->patch_count()) + "), found " +
                                             std::to_string(c.shape[0]));
    for (std::size_t p = 0; p < c.shape[0]; ++p) {
      const float* row = &c.data[closure_column::kCount * p];
      const float closure = row[closure_column::kClosure], scale = row[closure_column::kRowScale];
      if (!(closure >= 0.0f && closure <= 1.0f) || !(scale >= 0.0f) || !std::isfinite(scale))
        throw Error(closure_file.string(), "row " + std::to_string(p) +
                                               ": closure must lie in [0, 1] and the row "
                                               "scale be finite and >= 0");
      data->closure.push_back(closure);
      data->row_scale.push_back(scale);
    }
  }

  if (!scene) {
    // A bake folder names its scene; show the mesh when it is still there.
    const fs::path& path = data->bake.description.scene_path;
    if (!path.empty() && fs::exists(path)) {
      Diagnostics quiet;
      scene = std::make_shared<const Scene>(SceneLoader(quiet).load(path));
    }
  }
  data->scene = std::move(scene);
  return data;
}

}  // namespace bounce::views
