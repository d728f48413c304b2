#pragma once
// One bake as the studio runs it: load the scene, run the core Baker (the
// same call as `bounce bake`), write the bake folder with the core writer,
// and read it back for the views. Runs on any thread; the GUI runs it on a
// worker thread (bake_controller.h), headless screenshots run it directly.
#include <filesystem>
#include <memory>

#include "bake/bake.h"
#include "bake_view_data.h"
#include "base/diagnostics.h"
#include "base/progress.h"

namespace bounce::studio {

struct BakeJobResult {
  std::shared_ptr<const Scene> scene;
  std::shared_ptr<const BakeResult> result;
  std::shared_ptr<Diagnostics> diagnostics;
  std::filesystem::path folder;
  std::shared_ptr<const views::BakeViewData> data;
};

// Throws bounce::Error (Cancelled when progress asks to stop).
BakeJobResult run_bake_job(const std::filesystem::path& scene_path, const BakeSettings& settings,
                           const std::filesystem::path& folder, Progress& progress);

// Exports a finished bake: the same folder format as `bounce bake --out`.
void export_bake(const BakeJobResult& job, const std::filesystem::path& folder);

// True if `path` is a bake folder (it holds a manifest.json) rather than a scene.
bool is_bake_folder(const std::filesystem::path& path);

}  // namespace bounce::studio
