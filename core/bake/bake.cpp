#include "bake/bake.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <span>
#include <string>
#include <string_view>

#include "bake/bake_key.h"
#include "bake/bake_steps.h"

namespace bounce {

namespace {

int dominant_direction(const glm::vec3& n) {
  const glm::vec3 a = glm::abs(n);
  const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
  return 2 * axis + (n[axis] < 0.0f ? 1 : 0);
}

std::size_t predicted_patches(const Scene& scene, const Voxelization& vox, int per_voxel,
                              PatchMode mode) {
  if (mode == PatchMode::Virtual) return vox.voxels.size() * static_cast<std::size_t>(per_voxel);
  std::size_t count = 0;
  for (const OccupiedVoxel& v : vox.voxels) {
    std::set<int> directions;
    for (std::uint32_t k = 0; k < v.part_count; ++k) {
      const std::uint32_t t = vox.parts[v.first_part + k].triangle;
      const glm::vec3 n = scene.triangle_cross(t);
      directions.insert(dominant_direction(n));
      if (scene.two_sided(t)) directions.insert(dominant_direction(-n));
    }
    count += directions.size();
  }
  return count;
}

std::span<const BakeStep> steps_of(BakeStage stage) {
  switch (stage) {
    case BakeStage::Geometry:
      return geometry_steps();
    case BakeStage::Patches:
      return patch_steps();
    case BakeStage::FormFactors:
      return form_factor_steps();
    case BakeStage::Transport:
      return transport_steps();
    case BakeStage::Compress:
      return compression_steps();
    case BakeStage::None:
      break;
  }
  return {};
}

// The timings of the steps a re-bake does not run, as they were measured
// when they ran (a re-bake of a re-bake lists what it reused in turn, under
// the same name). The ray tracer's step belongs to two stages: a run from the
// patches builds it again, so it is reused only when no stage that runs
// times it.
void reuse_timings(const RebakePlan& plan, const BakeResult& previous, BakeResult& r) {
  static constexpr std::string_view kReused = " (reused)";
  std::set<std::string_view> reused, timed_again;
  for (std::size_t s = 0; s < kBakeStageCount; ++s)
    for (const BakeStep& step : steps_of(static_cast<BakeStage>(s)))
      if (step.timing)
        (plan.runs(static_cast<BakeStage>(s)) ? timed_again : reused).insert(step.timing);
  for (const StageStats& st : previous.stages) {
    std::string_view name = st.name;
    if (name.ends_with(kReused)) name.remove_suffix(kReused.size());
    if (!reused.contains(name) || timed_again.contains(name)) continue;
    r.stages.push_back(st);
    r.stages.back().name = std::string(name) + std::string(kReused);
  }
}

// The diagnostics a stage the re-bake does not run raised when it ran.
void reuse_diagnostics(BakeStage stage, const BakeResult& previous, Diagnostics& diagnostics) {
  for (const Diagnostic& d : previous.stage_diagnostics[static_cast<std::size_t>(stage)]) {
    if (d.kind == Diagnostic::Kind::Warning)
      diagnostics.warn(d.where, d.message, d.detail);
    else
      diagnostics.left_out(d.where, d.message);
  }
}

// What the stages before plan.first made, from `previous`. From the patches
// on only the voxels and samples (with the settings that resolved the grid,
// and the diagnostics a stage that runs replaces): copying the form factors
// and transport only to replace them would double the bake's memory for a
// while. The later stages never modify the voxels or samples (they prune
// patches and number the samples' patches in patch_of_sample), so these are
// the samples as the geometry stage made them.
void take_reused(BakeStage first, const BakeResult& previous, BakeResult& r) {
  if (first != BakeStage::Patches) {
    r = previous;
    r.stages.clear();
    return;
  }
  r.settings = previous.settings;
  r.voxels = previous.voxels;
  r.samples = previous.samples;
  r.stage_diagnostics = previous.stage_diagnostics;
}

// Runs a stage's steps that apply, each timed under its own name, when the
// plan runs the stage, and keeps the diagnostics they raise for a re-bake
// that reuses the stage.
void run_stage(BakeStage stage, BakeRun& run) {
  if (!run.result.plan.runs(stage)) return;
  const std::size_t diagnostics_before = run.diagnostics.all().size();
  for (const BakeStep& step : steps_of(stage)) {
    if (step.applies && !step.applies(run)) continue;
    if (step.timing) {
      const StageTimer timer(step.timing);
      step.run(run);
      run.result.stages.push_back(timer.finish());
    } else {
      step.run(run);
    }
    // A stop asked for during a step whose loops no longer polled (its last
    // report) ends the bake here, not after the stages that follow.
    run.progress.check();
    if (run.finished) return;
  }
  const std::vector<Diagnostic> all = run.diagnostics.all();
  run.result.stage_diagnostics[static_cast<std::size_t>(stage)].assign(
      all.begin() + static_cast<std::ptrdiff_t>(std::min(diagnostics_before, all.size())),
      all.end());
}

}  // namespace

int Baker::resolution_for_patch_count(const Scene& scene, int patches_total, int per_voxel,
                                      PatchMode mode) {
  const Bounds bounds = scene.bounds();
  // Patch count grows monotonically (roughly as r^2 for surfaces) with the
  // resolution r: bisect on r.
  int lo = 1, hi = 1;
  auto count_at = [&](int r) {
    return predicted_patches(scene, voxelize(scene, VoxelGrid(bounds, r)), per_voxel, mode);
  };
  const auto target = static_cast<std::size_t>(patches_total);
  while (hi < VoxelGrid::kMaxResolution && count_at(hi) < target)
    hi = std::min(2 * hi, VoxelGrid::kMaxResolution);
  lo = std::max(1, hi / 2);
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    (count_at(mid) < target ? lo : hi) = mid;
  }
  const auto dist = [&](int r) {
    const double c = static_cast<double>(count_at(r));
    return std::abs(std::log(c / static_cast<double>(target)));
  };
  return dist(lo) <= dist(hi) ? lo : hi;
}

BakeResult Baker::run(Progress& progress, const BakeResult* previous) const {
  const auto start = std::chrono::steady_clock::now();
  BakeResult r;
  RebakePlan plan;  // a full bake
  if (previous) {
    plan = plan_rebake(scene_, previous->settings, previous->patch_density, settings_);
    if (plan.first != BakeStage::Geometry) {
      take_reused(plan.first, *previous, r);
      reuse_timings(plan, *previous, r);
      for (std::size_t s = 0; s < kBakeStageCount; ++s)
        if (!plan.runs(static_cast<BakeStage>(s)))
          reuse_diagnostics(static_cast<BakeStage>(s), *previous, diagnostics_);
    }
  }
  const std::optional<int> resolved_resolution =
      plan.runs(BakeStage::Geometry) ? std::nullopt : r.settings.voxel_resolution;
  r.settings = settings_;
  r.requested = settings_;
  r.settings.apply_scene_defaults(scene_.defaults);
  r.settings.validate();
  if (resolved_resolution) r.settings.voxel_resolution = resolved_resolution;
  r.plan = plan;

  BakeRun bake{.scene = scene_,
               .diagnostics = diagnostics_,
               .distribution = distribution_,
               .progress = progress,
               .result = r};
  const std::optional<std::string> content = content_given_ ? content_ : scene_content_hash(scene_);
  r.key = content ? bake_key(*content, scene_, settings_) : std::string();
  // Each stage, then tells the listener its results are in (run, or reused).
  const auto stage = [&](BakeStage s) {
    run_stage(s, bake);
    if (stage_done_ && !bake.finished) stage_done_(s, r);
  };
  stage(BakeStage::Geometry);
  stage(BakeStage::Patches);
  // Out of core: F is computed on the heap and moved to a mapped file once
  // final (after the checks), the transport maps each finished T (see
  // spill_to_file: matrices being written stay on the heap).
  r.out_of_core = decide_out_of_core(r.settings, r.patches.size());
  bake.out_of_core = policy_of(r.out_of_core);
  if (distribution_ && !plan.runs(BakeStage::FormFactors))
    throw Error("bake", "a distributed bake cannot reuse an earlier bake's form factors");
  stage(BakeStage::FormFactors);
  if (bake.finished) return r;  // a distributed bake's other process: the root holds the bake
  stage(BakeStage::Transport);
  stage(BakeStage::Compress);
  if (distribution_) {
    bake.compressor.reset();  // the other processes are done, and send their stages' peaks
    distribution_->add_other_ranks_peaks(r.stages);
  }
  r.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace bounce
