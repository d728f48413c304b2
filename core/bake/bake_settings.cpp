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
  // The scene's budget only where a budget applies: a kept fraction, the
  // paper's pipeline and the dense matrix each decide the matrix otherwise.
  if (!error_budget && d.error_budget && !kept_fraction && codec != CodecChoice::Paper &&
      codec != CodecChoice::Dense)
    error_budget = d.error_budget;
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
  require(closure_rays >= 0 && closure_rays <= 65536, "--closure-rays",
          "must be between 0 (no balancing) and 65536, got " + std::to_string(closure_rays));
  require(
      final_gather_rays >= 0 && final_gather_rays <= 65536, "--final-gather-rays",
      "must be between 0 (no final gather) and 65536, got " + std::to_string(final_gather_rays));
  require(transport.bounces >= TransportSettings::kInfiniteBounces &&
              transport.bounces <= TransportSettings::kMaxBounces,
          "--bounces",
          "must be auto, inf or 1.." + std::to_string(TransportSettings::kMaxBounces) + ", got " +
              std::to_string(transport.bounces));
  if (kept_fraction)
    require(*kept_fraction >= 0.0 && *kept_fraction <= 1.0, "--kept-fraction",
            "must be between 0 and 1, got " + std::to_string(*kept_fraction));
  if (error_budget)
    require(*error_budget > 0.0 && *error_budget < 1.0, "--error-budget",
            "must be between 0 and 1 (exclusive), got " + std::to_string(*error_budget));
  if (size_limit)
    require(*size_limit > 0.0 && *size_limit <= 1.0, "--size-limit",
            "must be a share of the dense float32 RGB matrix above 0 and at most 1, got " +
                std::to_string(*size_limit));
  require(!(size_limit &&
            (kept_fraction || codec == CodecChoice::Paper || codec == CodecChoice::Dense)),
          "--size-limit",
          "only bounds the error budget's search (--codec auto or ours without "
          "--kept-fraction)");
  require(!(kept_fraction && error_budget), "--error-budget",
          "cannot be combined with --kept-fraction: the budget chooses the kept fraction");
  require(!(codec == CodecChoice::Paper && error_budget), "--error-budget",
          "does not apply to --codec paper, which keeps the published 4% (use --kept-fraction)");
  require(!(codec == CodecChoice::Dense && (kept_fraction || error_budget)),
          kept_fraction ? "--kept-fraction" : "--error-budget",
          "does not apply to --codec dense, which stores the exact matrix");
}

const char* to_string(OutOfCore mode) {
  switch (mode) {
    case OutOfCore::Auto:
      return "auto";
    case OutOfCore::On:
      return "on";
    case OutOfCore::Off:
      return "off";
  }
  return "?";
}

std::string to_string(PatchMode mode) { return mode == PatchMode::Virtual ? "virtual" : "voxel"; }

const char* to_string(CodecChoice codec) {
  switch (codec) {
    case CodecChoice::Auto:
      return "auto";
    case CodecChoice::Dense:
      return "dense";
    case CodecChoice::Paper:
      return "paper";
    case CodecChoice::Ours:
      return "ours";
  }
  return "?";
}

}  // namespace bounce
