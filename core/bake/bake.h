#pragma once
// The bake pipeline: voxel grid, samples, patches (virtual or voxel
// baseline), form factors, checks, the multi-bounce transport matrix and its
// storage (dense or compressed, with errors). The CLI and the
// studio both call Baker::run.
#include <vector>

#include "bake/bake_settings.h"
#include "bake/matrix_storage.h"
#include "base/diagnostics.h"
#include "base/progress.h"
#include "base/stage_stats.h"
#include "formfactor/form_factors.h"
#include "patches/clustering.h"
#include "patches/patch_set.h"
#include "patches/samples.h"
#include "transport/transport.h"
#include "voxel/voxelization.h"

namespace bounce {

struct BakeResult {
  BakeSettings settings;  // as resolved (grid resolution filled in)
  Voxelization voxels;
  SampleSet samples;
  PatchSet patches;
  // Patch index of each sample (-1 when its patch was left out).
  std::vector<std::int32_t> patch_of_sample;
  FormFactorMatrix form_factors;
  FormFactorChecks checks;
  ClusteringStats clustering;
  std::size_t patches_before_pruning = 0;
  TransportResult transport;  // multi-bounce matrices, exact
  // The first-hit light of the evaluation lights (runtime/direct_light.h),
  // against which the indirect-light error of compression is measured.
  IndirectLightProbe probe;
  std::size_t probe_lights_total = 0;  // evaluation lights, dark ones included
  MatrixStorage storage;               // how T is stored, and its errors
  std::vector<StageStats> stages;
  double total_seconds = 0.0;
};

class Baker {
 public:
  Baker(const Scene& scene, BakeSettings settings, Diagnostics& diagnostics)
      : scene_(scene), settings_(std::move(settings)), diagnostics_(diagnostics) {}

  // Runs every stage; throws Cancelled if progress asks to stop.
  BakeResult run(Progress& progress) const;

  // Grid resolution for a target patch count: the resolution whose predicted
  // patch count (occupied voxels x patches per voxel, or voxel-direction
  // pairs for the voxel baseline) comes closest.
  static int resolution_for_patch_count(const Scene& scene, int patches_total,
                                        int patches_per_voxel, PatchMode mode);

 private:
  const Scene& scene_;
  BakeSettings settings_;
  Diagnostics& diagnostics_;
};

}  // namespace bounce
