#include "settings/bake_settings.h"

#include <string>

#include "runtime/probe_volume.h"
#include "settings/settings_table.h"

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
  if (!error_budget && d.error_budget && !kept_fraction && codec != CodecChoice::LargestEntries &&
      codec != CodecChoice::Dense)
    error_budget = d.error_budget;
  if (light_probes == ProbePlacementMode::Auto && d.light_probes)
    setting_row("light_probes").set(*this, *d.light_probes);
  if (light_probe_volumes.empty()) light_probe_volumes = d.light_probe_volumes;
}

static void require(bool ok, const char* setting, const std::string& what) {
  if (!ok) throw BakeSettings::InvalidSetting(setting, what);
}

void BakeSettings::validate() const {
  for (const SettingRow& row : settings_table()) check_setting(row, row.get(*this));
  require(!(size_limit &&
            (kept_fraction || codec == CodecChoice::LargestEntries || codec == CodecChoice::Dense)),
          "size_limit",
          "only bounds the error budget's search (codec auto or ours without a kept fraction)");
  require(!(kept_fraction && error_budget), "error_budget",
          "cannot be combined with kept_fraction: the budget chooses the kept fraction");
  require(!(codec == CodecChoice::LargestEntries && error_budget), "error_budget",
          "does not apply to codec paper, which keeps the published 4% (set kept_fraction)");
  require(!(codec == CodecChoice::Dense && (kept_fraction || error_budget)),
          kept_fraction ? "kept_fraction" : "error_budget",
          "does not apply to codec dense, which stores the exact matrix");
  std::vector<ProbeVolume> volumes;
  try {
    volumes = parse_probe_volumes(light_probe_volumes, "light_probe_volumes");
  } catch (const Error& e) {
    // The same message, as the setting's own error (the front ends name its option).
    throw InvalidSetting("light_probe_volumes", std::string(e.what()).substr(e.where().size() + 2));
  }
  require(!(light_probes == ProbePlacementMode::VolumesOnly && volumes.empty()), "light_probes",
          "is 'volumes' but there is no probe volume (set light_probe_volumes)");
}

const char* to_string(ProbePlacementMode mode) {
  switch (mode) {
    case ProbePlacementMode::Auto:
      return "auto";
    case ProbePlacementMode::On:
      return "on";
    case ProbePlacementMode::VolumesOnly:
      return "volumes";
    case ProbePlacementMode::Off:
      return "off";
  }
  return "?";
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
    case CodecChoice::LargestEntries:
      return "paper";
    case CodecChoice::LightWeighted:
      return "ours";
  }
  return "?";
}

}  // namespace bounce
