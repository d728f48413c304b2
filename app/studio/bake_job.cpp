#include "bake_job.h"

#include "bake/bake_writer.h"
#include "scene/scene_loader.h"

namespace bounce::studio {

namespace fs = std::filesystem;

BakeJobResult run_bake_job(const fs::path& scene_path, const BakeSettings& settings,
                           const fs::path& folder, Progress& progress) {
  settings.validate();
  BakeJobResult job;
  job.diagnostics = std::make_shared<Diagnostics>();
  job.scene = std::make_shared<const Scene>(SceneLoader(*job.diagnostics).load(scene_path));
  job.result = std::make_shared<const BakeResult>(
      Baker(*job.scene, settings, *job.diagnostics).run(progress));
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

bool is_bake_folder(const fs::path& path) {
  return fs::is_directory(path) && fs::exists(path / "manifest.json");
}

}  // namespace bounce::studio
