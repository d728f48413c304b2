#include "bake/rebake_plan.h"

#include <algorithm>

#include "bake/bake.h"
#include "settings/settings_table.h"
#include "transport/text_format.h"

namespace bounce {

namespace {

// The grid resolution `settings` (scene defaults applied) bakes at, without
// the bisection when `previous` already resolved the same patch target.
int grid_resolution(const Scene& scene, const BakeSettings& previous, const BakeSettings& s) {
  if (s.voxel_resolution) return *s.voxel_resolution;
  if (!s.patches_total) return BakeSettings::kDefaultVoxelResolution;
  if (previous.patches_total == s.patches_total &&
      previous.patches_per_voxel == s.patches_per_voxel && previous.patch_mode == s.patch_mode &&
      previous.voxel_resolution)
    return *previous.voxel_resolution;
  return Baker::resolution_for_patch_count(scene, *s.patches_total, *s.patches_per_voxel,
                                           s.patch_mode);
}

// `what` changed, which re-runs `stage` and every later one.
void rerun(RebakePlan& plan, BakeStage stage, const std::string& what) {
  plan.reasons.push_back(what + " (re-runs from " + std::string(to_string(stage)) + ")");
  plan.first = std::min(plan.first, stage);
}

}  // namespace

const char* to_string(BakeStage stage) {
  switch (stage) {
    case BakeStage::Geometry:
      return "geometry";
    case BakeStage::Patches:
      return "patches";
    case BakeStage::FormFactors:
      return "form factors";
    case BakeStage::Transport:
      return "transport";
    case BakeStage::Compress:
      return "compress";
    case BakeStage::None:
      break;
  }
  return "none";
}

RebakePlan plan_rebake(const Scene& scene, const BakeSettings& previous, const BakeSettings& next) {
  BakeSettings s = next;
  s.apply_scene_defaults(scene.defaults);
  RebakePlan plan;
  plan.first = BakeStage::None;
  const auto changed = [&plan](bool differs, BakeStage stage, const std::string& what) {
    if (differs) rerun(plan, stage, what);
  };

  // The grid rows together, by the resolution they resolve to.
  const int old_resolution = previous.voxel_resolution.value_or(-1);
  const int new_resolution = grid_resolution(scene, previous, s);
  changed(old_resolution != new_resolution, BakeStage::Geometry,
          text_format("voxel resolution: %d -> %d", old_resolution, new_resolution));
  for (const SettingRow& row : settings_table()) {
    if (row.grid || row.stage == BakeStage::None) continue;
    const SettingValue a = row.get(previous), b = row.get(s);
    changed(a != b, row.stage,
            std::string(row.name) + ": " + setting_text(row, a) + " -> " + setting_text(row, b));
  }
  // Not settings a user gives, but they decide the transport too.
  const TransportSettings &a = previous.transport, &b = s.transport;
  changed(a.auto_tolerance != b.auto_tolerance || a.max_auto_bounces != b.max_auto_bounces,
          BakeStage::Transport, "automatic bounce limit");
  return plan;
}

std::vector<float> patch_densities(const Scene& scene) {
  std::vector<float> d;
  d.reserve(scene.meshes.size());
  for (const MeshInfo& m : scene.meshes) d.push_back(m.patch_density);
  return d;
}

RebakePlan plan_rebake(const Scene& scene, const BakeSettings& previous,
                       const std::vector<float>& previous_densities, const BakeSettings& next) {
  RebakePlan plan = plan_rebake(scene, previous, next);
  const std::vector<float> now = patch_densities(scene);
  if (now == previous_densities) return plan;
  // Another number of meshes: not the previous bake's scene, whose voxels
  // and samples cannot be reused.
  if (now.size() != previous_densities.size()) {
    rerun(plan, BakeStage::Geometry,
          text_format("patch densities of %zu meshes, the previous bake had %zu", now.size(),
                      previous_densities.size()));
    return plan;
  }
  // The voxels and samples do not depend on the densities: the clustering
  // and what follows it run again.
  for (std::size_t i = 0; i < now.size(); ++i)
    if (now[i] != previous_densities[i])
      rerun(plan, BakeStage::Patches,
            "patch density of '" + scene.meshes[i].name +
                "': " + text_format("%g -> %g", previous_densities[i], now[i]));
  return plan;
}

}  // namespace bounce
