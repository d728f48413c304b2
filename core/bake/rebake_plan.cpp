#include "bake/rebake_plan.h"

#include <algorithm>

#include "bake/bake.h"
#include "transport/text_format.h"

namespace bounce {

namespace {

std::string bounces_text(int bounces) {
  if (bounces == TransportSettings::kAutoBounces) return "auto";
  if (bounces == TransportSettings::kInfiniteBounces) return "inf";
  return std::to_string(bounces);
}

std::string optional_text(const std::optional<double>& v) {
  return v ? text_format("%g", *v) : std::string("default");
}

std::string ordering_text(const std::optional<OrderingMethod>& o) {
  return o ? ordering_name(*o) : "codec's own";
}

const char* backend_text(TransportSettings::Backend b) {
  switch (b) {
    case TransportSettings::Backend::OpenBLAS:
      return "openblas";
    case TransportSettings::Backend::CLBlast:
      return "clblast";
    case TransportSettings::Backend::Auto:
      break;
  }
  return "auto";
}

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

}  // namespace

const char* to_string(BakeStage stage) {
  switch (stage) {
    case BakeStage::Geometry:
      return "geometry";
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
    if (!differs) return;
    plan.reasons.push_back(what + " (re-runs from " + std::string(to_string(stage)) + ")");
    if (static_cast<int>(stage) < static_cast<int>(plan.first)) plan.first = stage;
  };

  const int old_resolution = previous.voxel_resolution.value_or(-1);
  const int new_resolution = grid_resolution(scene, previous, s);
  changed(old_resolution != new_resolution, BakeStage::Geometry,
          text_format("voxel resolution: %d -> %d", old_resolution, new_resolution));
  changed(previous.patches_per_voxel != s.patches_per_voxel, BakeStage::Geometry,
          text_format("patches per voxel: %d -> %d", previous.patches_per_voxel.value_or(0),
                      s.patches_per_voxel.value_or(0)));
  changed(previous.patch_mode != s.patch_mode, BakeStage::Geometry,
          "patches: " + to_string(previous.patch_mode) + " -> " + to_string(s.patch_mode));
  changed(previous.samples_per_face != s.samples_per_face, BakeStage::Geometry,
          text_format("samples per face: %d -> %d", previous.samples_per_face.value_or(0),
                      s.samples_per_face.value_or(0)));
  changed(previous.seed != s.seed, BakeStage::Geometry,
          text_format("seed: %llu -> %llu", static_cast<unsigned long long>(previous.seed),
                      static_cast<unsigned long long>(s.seed)));

  // Visibility rays change the form factors, and with them which patches the
  // checks prune (those that see nothing), so the patch set itself: the
  // pruned patches of the previous bake cannot be reused.
  changed(previous.visibility_rays != s.visibility_rays, BakeStage::Geometry,
          text_format("visibility rays: %d -> %d", previous.visibility_rays, s.visibility_rays));

  // The closure and the balancing to it change F; its rays need the tracer,
  // which only a run from geometry builds (see BakeStage).
  changed(previous.closure_rays != s.closure_rays, BakeStage::Geometry,
          text_format("closure rays: %d -> %d", previous.closure_rays, s.closure_rays));

  changed(
      previous.final_gather_rays != s.final_gather_rays, BakeStage::Geometry,
      text_format("final gather rays: %d -> %d", previous.final_gather_rays, s.final_gather_rays));

  const TransportSettings &a = previous.transport, &b = s.transport;
  changed(a.bounces != b.bounces, BakeStage::Transport,
          "bounces: " + bounces_text(a.bounces) + " -> " + bounces_text(b.bounces));
  changed(a.auto_tolerance != b.auto_tolerance || a.max_auto_bounces != b.max_auto_bounces,
          BakeStage::Transport, "automatic bounce limit");
  // The backends round differently: the matrices are not bit-identical.
  changed(a.backend != b.backend, BakeStage::Transport,
          std::string("matrix products: ") + backend_text(a.backend) + " -> " +
              backend_text(b.backend));

  changed(previous.codec != s.codec, BakeStage::Compress,
          std::string("codec: ") + to_string(previous.codec) + " -> " + to_string(s.codec));
  changed(previous.kept_fraction != s.kept_fraction, BakeStage::Compress,
          "kept fraction: " + optional_text(previous.kept_fraction) + " -> " +
              optional_text(s.kept_fraction));
  changed(previous.error_budget != s.error_budget, BakeStage::Compress,
          "error budget: " + optional_text(previous.error_budget) + " -> " +
              optional_text(s.error_budget));
  changed(
      previous.size_limit != s.size_limit, BakeStage::Compress,
      "size limit: " + optional_text(previous.size_limit) + " -> " + optional_text(s.size_limit));
  changed(previous.ordering != s.ordering, BakeStage::Compress,
          "ordering: " + ordering_text(previous.ordering) + " -> " + ordering_text(s.ordering));
  return plan;
}

}  // namespace bounce
