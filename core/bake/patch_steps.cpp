// The patch stage of a bake: the patches, clustered from the geometry
// stage's samples. A change of a mesh's patch density re-runs from here, so
// a re-bake that reuses the voxels and samples builds the ray tracer here,
// which the clustering and the form factors trace with.
#include <string>

#include "bake/bake_steps.h"

namespace bounce {

namespace {

bool has_no_tracer(const BakeRun& run) { return !run.tracer; }

// Reads the samples and voxels only: a re-bake from here takes them as the
// previous bake left them (nothing after this stage changes them either:
// the checks prune patches and number the samples' patches in
// BakeResult::patch_of_sample).
void patches_step(BakeRun& run) {
  BakeResult& r = run.result;
  if (r.settings.patch_mode == PatchMode::Virtual) {
    ClusteringSettings c;
    c.patches_per_voxel = *r.settings.patches_per_voxel;
    // A total patch count is a total: the grid was chosen for it at
    // patches_per_voxel, the merges then go where they cost least.
    if (r.settings.patches_total)
      c.total_patches = static_cast<std::size_t>(*r.settings.patches_total);
    c.mesh_density = patch_densities(run.scene);
    if (run.distribution) c.sharing = run.distribution->sample_row_sharing();
    r.patches =
        cluster_virtual_patches(*run.tracer, r.voxels, r.samples, c, r.clustering, &run.progress);
    if (r.clustering.voxels_above_target > 0)
      run.diagnostics.warn("patches", std::to_string(r.clustering.voxels_above_target) +
                                          " voxels kept more than " +
                                          std::to_string(*r.settings.patches_per_voxel) +
                                          " patches: their samples face opposite ways or stand "
                                          "on two sides of a surface, and are never merged");
  } else {
    run.progress.begin_stage("voxel patches", 1);
    r.patches = voxel_patches(r.samples);
    run.progress.end_stage();
  }
  r.patch_density = patch_densities(run.scene);
}

constexpr BakeStep kPatchSteps[] = {
    {kTracerTiming, has_no_tracer, build_tracer},
    {"patches", nullptr, patches_step},
};

}  // namespace

std::span<const BakeStep> patch_steps() { return kPatchSteps; }

}  // namespace bounce
