#pragma once
// The bake pipeline: voxel grid, samples, patches (virtual or voxel
// baseline), form factors, checks, the multi-bounce transport matrix and its
// storage (dense or compressed, with errors). The CLI and the
// studio both call Baker::run.
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bake/bake_distribution.h"
#include "bake/matrix_storage.h"
#include "bake/out_of_core.h"
#include "bake/rebake_plan.h"
#include "base/diagnostics.h"
#include "base/progress.h"
#include "base/stage_stats.h"
#include "formfactor/balance.h"
#include "formfactor/closure.h"
#include "formfactor/form_factors.h"
#include "patches/clustering.h"
#include "patches/patch_set.h"
#include "patches/samples.h"
#include "runtime/final_gather.h"
#include "runtime/light_probe_placement.h"
#include "runtime/light_probes.h"
#include "settings/bake_settings.h"
#include "transport/transport.h"
#include "voxel/voxelization.h"

namespace bounce {

struct BakeResult {
  BakeSettings settings;   // as resolved (grid resolution filled in)
  BakeSettings requested;  // as given to the Baker, before the scene's defaults
  Voxelization voxels;
  SampleSet samples;
  PatchSet patches;
  // Patch index of each sample (-1 when its patch was left out).
  std::vector<std::int32_t> patch_of_sample;
  FormFactorMatrix form_factors;  // balanced to the closure unless closure_rays is 0
  FormFactorChecks checks;        // of form_factors as stored
  FormFactorChecks checks_raw;    // of the quadrature, before balancing
  PatchClosure closure;           // empty when closure_rays is 0
  // The final gather of the lit mesh's vertices (empty rows when
  // final_gather_rays is 0), and what it took.
  FinalGather vertex_gather;
  // The light probes and their gather (none unless settings.light_probes),
  // and how the placement went (its positions are light_probes.position).
  LightProbes light_probes;
  ProbePlacement probe_placement;
  BalanceStats balance;
  ClusteringStats clustering;
  // Each mesh's patch density the patches were made with: a re-bake of a
  // scene whose densities differ cannot reuse them.
  std::vector<float> patch_density;
  std::size_t patches_before_pruning = 0;
  TransportResult transport;  // multi-bounce matrices, exact
  // The first-hit light of the evaluation lights (runtime/direct_light.h),
  // against which the indirect-light error of compression is measured.
  IndirectLightProbe probe;
  std::size_t probe_lights_total = 0;  // evaluation lights, dark ones included
  MatrixStorage storage;               // how T is stored, and its errors
  // Whether F and T were moved to memory-mapped files once finished (decided
  // once the patch count is known; a re-bake decides again).
  OutOfCoreDecision out_of_core;
  // Stages of this run; those taken from a previous bake carry "(reused)".
  std::vector<StageStats> stages;
  double total_seconds = 0.0;  // of this run only
  // What this run re-ran (first = Geometry for a full bake) and why.
  RebakePlan plan;
  // The warnings and left-out notes each stage raised (indexed by BakeStage),
  // repeated into the diagnostics of a re-bake that reuses the stage.
  std::array<std::vector<Diagnostic>, kBakeStageCount> stage_diagnostics;
  // The content key of the scene's files and these settings (bake/bake_key.h),
  // written to the manifest so a bake of the same inputs can be reused;
  // empty for a scene not read from files (built in memory).
  std::string key;
};

// Called by Baker::run once a stage's results are in the BakeResult (run, or
// taken from the previous bake), on the thread that runs the bake, before the
// next stage starts: a front end can show partial results (the patches while
// the form factors run). Copy what is needed: `partial` changes afterwards.
using StageDone = std::function<void(BakeStage stage, const BakeResult& partial)>;

class Baker {
 public:
  Baker(const Scene& scene, BakeSettings settings, Diagnostics& diagnostics)
      : scene_(scene), settings_(std::move(settings)), diagnostics_(diagnostics) {}

  // Runs every stage; throws Cancelled if progress asks to stop.
  BakeResult run(Progress& progress) const { return run(progress, nullptr); }
  // Re-bake: with `previous` (an earlier bake of the same scene), runs only
  // the stages plan_rebake says the settings change affects and takes the
  // earlier ones from `previous`. The result equals a full bake with these
  // settings (tests/unit/test_rebake.cpp).
  BakeResult run(Progress& progress, const BakeResult* previous) const;

  // Grid resolution for a target patch count: the resolution whose predicted
  // patch count (occupied voxels x patches per voxel, or voxel-direction
  // pairs for the voxel baseline) comes closest.
  static int resolution_for_patch_count(const Scene& scene, int patches_total,
                                        int patches_per_voxel, PatchMode mode);

  // Shares the bake with other processes (bake_distribution.h; a full bake
  // only, no `previous`). On a process that is not the root, run() returns
  // after the transport stage with the geometry only; the root's result is
  // the bake.
  void set_distribution(BakeDistribution* distribution) { distribution_ = distribution; }
  // The scene's content hash as taken when it was loaded
  // (scene_content_hash, bake/bake_key.h), for BakeResult::key; without it
  // run() hashes the scene's files as they are then. nullopt: none (a scene
  // whose files could not be read when loaded), the bake gets no key.
  void set_scene_content(std::optional<std::string> content) {
    content_ = std::move(content);
    content_given_ = true;
  }
  // See StageDone; null (the default): nobody is told.
  void set_stage_done(StageDone stage_done) { stage_done_ = std::move(stage_done); }

  // The voxel grid a bake with `settings` (scene defaults applied) starts
  // from, the first step of its geometry stage: fills in
  // settings.voxel_resolution as resolved (from patches_total, else the
  // default). Cheap next to the rest: front ends show it before the bake.
  static Voxelization voxel_grid(const Scene& scene, BakeSettings& settings, Progress* progress);

 private:
  const Scene& scene_;
  BakeSettings settings_;
  Diagnostics& diagnostics_;
  BakeDistribution* distribution_ = nullptr;
  StageDone stage_done_;
  std::optional<std::string> content_;
  bool content_given_ = false;
};

}  // namespace bounce
