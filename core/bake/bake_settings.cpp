#include "bake/bake_settings.h"

#include <string>

#include "voxel/voxel_grid.h"

namespace bounce {

void BakeSettings::apply_scene_defaults(const BakeDefaults& d) {
  if (!voxel_resolution && !patches_total) {
    if (d.voxel_resolution)
      voxel_resolution = d.voxel_resolution;
    else if (d.patches_total)
      patches_total = d.patches_total;
  }
  if (!patches_per_voxel) patches_per_voxel = d.patches_per_voxel.value_or(kDefaultPatchesPerVoxel);
  if (!samples_per_face) samples_per_face = d.samples_per_face.value_or(kDefaultSamplesPerFace);
}

static void require(bool ok, const char* option, const std::string& what) {
  if (!ok) throw BakeSettings::InvalidSetting(option, what);
}

void BakeSettings::validate() const {
  if (voxel_resolution)
    require(*voxel_resolution >= 1 && *voxel_resolution <= VoxelGrid::kMaxResolution, "--voxel",
            "must be between 1 and " + std::to_string(VoxelGrid::kMaxResolution) + ", got " +
                std::to_string(*voxel_resolution));
  if (patches_total)
    require(*patches_total >= 1 && *patches_total <= 1 << 20, "--patches-total",
            "must be between 1 and 1048576, got " + std::to_string(*patches_total));
  if (patches_per_voxel)
    require(*patches_per_voxel >= 1 && *patches_per_voxel <= 64, "--patches-per-voxel",
            "must be between 1 and 64, got " + std::to_string(*patches_per_voxel));
  if (samples_per_face)
    require(*samples_per_face >= 1 && *samples_per_face <= 64, "--samples-per-face",
            "must be between 1 and 64, got " + std::to_string(*samples_per_face));
  require(visibility_rays >= 1 && visibility_rays <= 1024, "--visibility-rays",
          "must be between 1 and 1024, got " + std::to_string(visibility_rays));
}

std::string to_string(PatchMode mode) { return mode == PatchMode::Virtual ? "virtual" : "voxel"; }

}  // namespace bounce
