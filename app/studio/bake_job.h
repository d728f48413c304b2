#pragma once
// One bake as the studio runs it: load the scene, run the core Baker (the
// same call as `bounce bake`), write the bake folder with the core writer,
// and read it back for the views. Runs on any thread; the GUI runs it on a
// worker thread (bake_controller.h), headless screenshots run it directly.
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bake_view_data.h"
#include "bounce/bake.h"
#include "bounce/bake_folder.h"

namespace bounce::studio {

struct BakeJobResult {
  std::filesystem::path scene_path;  // as given to run_bake_job
  std::shared_ptr<const Scene> scene;
  // The scene's files hashed when it was loaded (core scene_content_hash;
  // none when unreadable): a re-bake of this scene keys its bake by them,
  // not by the files as they are by then.
  std::optional<std::string> scene_content;
  // The last bake of this scene made in memory, what a re-bake starts from:
  // this job's, or with `reused` the previous job's (null if none).
  std::shared_ptr<const BakeResult> result;
  std::shared_ptr<Diagnostics> diagnostics;
  std::vector<Diagnostic> load_diagnostics;  // what loading the scene said
  std::filesystem::path folder;
  std::shared_ptr<const views::BakeViewData> data;
  // The folder was already in the bake cache with this job's key and is
  // shown as it is: nothing was baked.
  bool reused = false;
  // Why a cached folder with this key was not reused (corrupt, incomplete),
  // one line naming the file; empty otherwise.
  std::string cache_note;
};

struct BakeJobOptions {
  // `folder` is the bake cache: the bake goes to folder / <content key>
  // (core bake_key: the scene's file contents, the meshes' densities, the
  // settings), and a complete bake already there is shown instead of baking.
  bool cache = false;
  // Called on the job's thread with what the bake has made so far, for the
  // views to show before it ends: the voxel grid at once (not on a re-bake,
  // whose views show the last bake), then the samples and the patches as
  // their stages end. Throwing from it fails the job.
  std::function<void(std::shared_ptr<const views::BakeViewData>)> partial;
};

// Throws bounce::Error (Cancelled when progress asks to stop). With
// `previous`, an earlier job of the same scene path, its loaded scene is
// reused and only the stages the settings change affects run (the core's
// plan_rebake, Baker::run with a previous result); the rest is taken from it.
// `patch_density` (empty: the scene's own), one per mesh, replaces the
// meshes' patch densities (the studio's mesh list); a changed density
// re-runs the bake from its patch stage. Throws bounce::Error naming the
// scene when there is not one per mesh or one is not > 0 and <= 64.
BakeJobResult run_bake_job(const std::filesystem::path& scene_path, const BakeSettings& settings,
                           const std::filesystem::path& folder, Progress& progress,
                           std::shared_ptr<const BakeJobResult> previous = {},
                           const std::vector<float>& patch_density = {},
                           const BakeJobOptions& options = {});

// Exports a finished bake: the same folder format as `bounce bake --out`.
void export_bake(const BakeJobResult& job, const std::filesystem::path& folder);

}  // namespace bounce::studio
