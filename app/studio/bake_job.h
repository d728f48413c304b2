#pragma once
// One bake as the studio runs it: load the scene, run the core Baker (the
// same call as `bounce bake`), write the bake folder with the core writer,
// and read it back for the views. Runs on any thread; the GUI runs it on a
// worker thread (bake_controller.h), headless screenshots run it directly.
#include <filesystem>
#include <memory>
#include <vector>

#include "bake_view_data.h"
#include "bounce/bake.h"
#include "bounce/bake_folder.h"

namespace bounce::studio {

struct BakeJobResult {
  std::filesystem::path scene_path;  // as given to run_bake_job
  std::shared_ptr<const Scene> scene;
  std::shared_ptr<const BakeResult> result;
  std::shared_ptr<Diagnostics> diagnostics;
  std::vector<Diagnostic> load_diagnostics;  // what loading the scene said
  std::filesystem::path folder;
  std::shared_ptr<const views::BakeViewData> data;
};

// Throws bounce::Error (Cancelled when progress asks to stop). With
// `previous`, an earlier job of the same scene path, its loaded scene is
// reused and only the stages the settings change affects run (the core's
// plan_rebake, Baker::run with a previous result); the rest is taken from it.
// `patch_density` (empty: the scene's own), one per mesh, replaces the
// meshes' patch densities (the studio's mesh list); a changed density
// re-runs the bake from its geometry stage. Throws bounce::Error naming the
// scene when there is not one per mesh or one is not > 0 and <= 64.
BakeJobResult run_bake_job(const std::filesystem::path& scene_path, const BakeSettings& settings,
                           const std::filesystem::path& folder, Progress& progress,
                           std::shared_ptr<const BakeJobResult> previous = {},
                           const std::vector<float>& patch_density = {});

// Exports a finished bake: the same folder format as `bounce bake --out`.
void export_bake(const BakeJobResult& job, const std::filesystem::path& folder);

}  // namespace bounce::studio
