// The geometry stage of a bake: voxel grid, ray tracer, samples and their
// albedo from textures and vertex colours.
#include <string>

#include "bake/bake_steps.h"

namespace bounce {

namespace {

void voxelize_step(BakeRun& run) {
  BakeResult& r = run.result;
  r.voxels = Baker::voxel_grid(run.scene, r.settings, &run.progress);
  const auto empty = r.voxels.grid.cell_count() - r.voxels.voxels.size();
  if (empty > 0)
    run.diagnostics.left_out("voxelize", std::to_string(empty) + " of " +
                                             std::to_string(r.voxels.grid.cell_count()) +
                                             " grid cells are empty and get no samples or patches");
}

void sample_step(BakeRun& run) {
  BakeResult& r = run.result;
  SamplingSettings s;
  s.samples_per_face = *r.settings.samples_per_face;
  s.seed = r.settings.seed;
  r.samples = generate_samples(run.scene, *run.tracer, r.voxels, s, &run.progress);
  if (r.samples.samples.empty())
    throw Error(run.scene.path,
                "no surface samples: no ray hit the scene's surfaces from inside any voxel");
}

// A step of its own, so that what textures and vertex colours cost shows in
// the manifest.
bool has_surface_detail(const BakeRun& run) {
  return !run.scene.triangle_uv.empty() || run.scene.has_vertex_colours();
}

void texture_step(BakeRun& run) {
  apply_surface_textures(run.scene, run.result.voxels, run.result.samples, &run.progress);
}

constexpr BakeStep kGeometrySteps[] = {
    {"voxelize", nullptr, voxelize_step},
    {kTracerTiming, nullptr, build_tracer},
    {"sample", nullptr, sample_step},
    {"texture", has_surface_detail, texture_step},
};

}  // namespace

Voxelization Baker::voxel_grid(const Scene& scene, BakeSettings& settings, Progress* progress) {
  int resolution = BakeSettings::kDefaultVoxelResolution;
  if (settings.voxel_resolution) {
    resolution = *settings.voxel_resolution;
  } else if (settings.patches_total) {
    if (progress) progress->begin_stage("choose grid resolution", 1);
    resolution = resolution_for_patch_count(scene, *settings.patches_total,
                                            *settings.patches_per_voxel, settings.patch_mode);
    if (progress) progress->end_stage();
  }
  settings.voxel_resolution = resolution;
  return voxelize(scene, VoxelGrid(scene.bounds(), resolution), progress);
}

void build_tracer(BakeRun& run) { run.tracer.emplace(run.scene); }

std::span<const BakeStep> geometry_steps() { return kGeometrySteps; }

}  // namespace bounce
