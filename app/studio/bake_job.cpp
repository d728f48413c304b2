#include "bake_job.h"

#include <string>

#include "bounce/bake.h"
#include "bounce/scene.h"

namespace bounce::studio {

namespace fs = std::filesystem;

BakeJobResult run_bake_job(const fs::path& scene_path, const BakeSettings& settings,
                           const fs::path& folder, Progress& progress,
                           std::shared_ptr<const BakeJobResult> previous,
                           const std::vector<float>& patch_density) {
  settings.validate();
  BakeJobResult job;
  job.scene_path = scene_path;
  job.diagnostics = std::make_shared<Diagnostics>();
  const bool rebake =
      previous && previous->result && previous->scene && previous->scene_path == scene_path;
  if (rebake) {
    // The scene's own warnings, which a fresh load would have raised again.
    job.load_diagnostics = previous->load_diagnostics;
    for (const Diagnostic& d : job.load_diagnostics) {
      if (d.kind == Diagnostic::Kind::Warning)
        job.diagnostics->warn(d.where, d.message);
      else
        job.diagnostics->left_out(d.where, d.message);
    }
    job.scene = previous->scene;
  } else {
    job.scene = std::make_shared<const Scene>(SceneLoader(*job.diagnostics).load(scene_path));
    job.load_diagnostics = job.diagnostics->all();
  }
  if (!patch_density.empty() && patch_density != patch_densities(*job.scene)) {
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
                               "' must be > 0 and <= " + std::to_string(kMaxPatchDensity) +
                               ", got " + std::to_string(d));
      edited->meshes[i].patch_density = d;
    }
    job.scene = std::move(edited);
  }
  job.result = std::make_shared<const BakeResult>(
      Baker(*job.scene, settings, *job.diagnostics)
          .run(progress, rebake ? previous->result.get() : nullptr));
  progress.check();
  write_bake(folder, *job.scene, *job.result, *job.diagnostics);
  job.folder = folder;
  job.data = views::load_bake_view_data(folder, job.scene);
  return job;
}

void export_bake(const BakeJobResult& job, const fs::path& folder) {
  if (!job.result) throw Error(folder.string(), "nothing to export: bake a scene first");
  write_bake(folder, *job.scene, *job.result, *job.diagnostics);
}

}  // namespace bounce::studio
