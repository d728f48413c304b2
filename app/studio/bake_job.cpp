#include "bake_job.h"

#include <string>

#include "bounce/bake.h"
#include "bounce/scene.h"
#include "partial_view_data.h"

namespace bounce::studio {

namespace fs = std::filesystem;

namespace {

// The scene to bake: the previous job's (a re-bake), else loaded afresh.
void take_scene(BakeJobResult& job, const fs::path& scene_path, const BakeJobResult* previous) {
  if (previous) {
    // The scene's own warnings, which a fresh load would have raised again.
    job.load_diagnostics = previous->load_diagnostics;
    for (const Diagnostic& d : job.load_diagnostics) {
      if (d.kind == Diagnostic::Kind::Warning)
        job.diagnostics->warn(d.where, d.message);
      else
        job.diagnostics->left_out(d.where, d.message);
    }
    job.scene = previous->scene;
    job.scene_content = previous->scene_content;
  } else {
    job.scene = std::make_shared<const Scene>(SceneLoader(*job.diagnostics).load(scene_path));
    job.load_diagnostics = job.diagnostics->all();
    job.scene_content = scene_content_hash(*job.scene);
  }
}

void apply_densities(BakeJobResult& job, const fs::path& scene_path,
                     const std::vector<float>& patch_density) {
  if (patch_density.empty() || patch_density == patch_densities(*job.scene)) return;
  const std::string where = scene_path.string();
  if (patch_density.size() != job.scene->meshes.size())
    throw Error(where, std::to_string(patch_density.size()) +
                           " patch densities given for a scene of " +
                           std::to_string(job.scene->meshes.size()) + " meshes");
  // A copy: the previous job's scene stays as its bake had it.
  auto edited = std::make_shared<Scene>(*job.scene);
  for (std::size_t i = 0; i < patch_density.size(); ++i) {
    const float d = patch_density[i];
    if (!(d > 0.0f && d <= static_cast<float>(kMaxPatchDensity)))
      throw Error(where, "patch density of mesh '" + edited->meshes[i].name +
                             "' must be > 0 and <= " + std::to_string(kMaxPatchDensity) + ", got " +
                             std::to_string(d));
    edited->meshes[i].patch_density = d;
  }
  job.scene = std::move(edited);
}

// With the cache: the folder of this job's key, and whether a complete bake
// is there to show. A folder that cannot be shown is baked again, and
// job.cache_note says why.
bool find_in_cache(BakeJobResult& job, const BakeSettings& settings, const fs::path& cache) {
  const std::optional<std::string> key =
      job.scene_content ? std::optional(bake_key(*job.scene_content, *job.scene, settings))
                        : std::nullopt;
  // Without a key (a file of the scene unreadable since it was loaded) the
  // bake is not reusable: a folder of the scene's name, replaced each time.
  job.folder = cache / (key ? *key : job.scene->name + "-unkeyed");
  if (!key) return false;
  const std::optional<std::string> stored = stored_bake_key(job.folder, &job.cache_note);
  if (stored != key) return false;
  try {
    job.data = views::load_bake_view_data(job.folder, job.scene);
    return true;
  } catch (const std::exception& e) {
    job.cache_note = e.what();
    return false;
  }
}

}  // namespace

BakeJobResult run_bake_job(const fs::path& scene_path, const BakeSettings& settings,
                           const fs::path& folder, Progress& progress,
                           std::shared_ptr<const BakeJobResult> previous,
                           const std::vector<float>& patch_density, const BakeJobOptions& options) {
  settings.validate();
  BakeJobResult job;
  job.scene_path = scene_path;
  job.diagnostics = std::make_shared<Diagnostics>();
  const bool rebake =
      previous && previous->result && previous->scene && previous->scene_path == scene_path;
  take_scene(job, scene_path, rebake ? previous.get() : nullptr);
  apply_densities(job, scene_path, patch_density);
  job.folder = folder;
  if (options.cache && find_in_cache(job, settings, folder)) {
    job.reused = true;
    if (rebake) job.result = previous->result;
    return job;
  }
  if (!job.cache_note.empty())
    job.diagnostics->warn(job.folder.string(), "cached bake not reused: " + job.cache_note);
  Baker baker(*job.scene, settings, *job.diagnostics);
  baker.set_scene_content(job.scene_content);
  if (options.partial) {
    if (!rebake) {
      // The first picture: the grid is the cheap first step of the bake.
      BakeSettings resolved = settings;
      resolved.apply_scene_defaults(job.scene->defaults);
      BakeResult grid;
      // No progress of its own: the bake's voxelize bar follows at once.
      grid.voxels = Baker::voxel_grid(*job.scene, resolved, nullptr);
      options.partial(views::partial_view_data(job.scene, grid));
      progress.check();
    }
    baker.set_stage_done([&](BakeStage stage, const BakeResult& partial) {
      if (stage == BakeStage::Geometry || stage == BakeStage::Patches)
        options.partial(views::partial_view_data(job.scene, partial));
    });
  }
  job.result = std::make_shared<const BakeResult>(
      baker.run(progress, rebake ? previous->result.get() : nullptr));
  progress.check();
  write_bake(job.folder, *job.scene, *job.result, *job.diagnostics);
  job.data = views::load_bake_view_data(job.folder, job.scene);
  return job;
}

void export_bake(const BakeJobResult& job, const fs::path& folder) {
  if (!job.result || job.reused) {
    // A reused folder is the bake: copy it as it is.
    if (job.reused && !job.folder.empty()) {
      fs::copy(job.folder, folder,
               fs::copy_options::recursive | fs::copy_options::overwrite_existing);
      return;
    }
    throw Error(folder.string(), "nothing to export: bake a scene first");
  }
  write_bake(folder, *job.scene, *job.result, *job.diagnostics);
}

}  // namespace bounce::studio
