#pragma once
// Public: bake a scene and write the bake folder.
//
//   bounce::BakeSettings settings;          // every field optional
//   settings.error_budget = 0.02;
//   bounce::Progress progress(callback);    // (stage, fraction) -> false to stop
//   const bounce::BakeResult result = bounce::Baker(scene, settings, diagnostics).run(progress);
//   bounce::write_bake(folder, scene, result, diagnostics);
//
// Progress::request_stop() from any thread (or the callback returning false)
// stops the bake at its next check with bounce::Cancelled; a cancelled or
// failed write leaves no folder behind.
// Baker::run with a previous result re-runs only the stages the changed
// settings affect (bake/rebake_plan.h); Baker::set_stage_done hears each
// stage's partial results, Baker::voxel_grid gives the grid before a bake.
// bake_key(scene, settings) is the content key a manifest records, and
// stored_bake_key(folder) the key of a complete bake in a folder: equal keys,
// the same bake (bake/bake_key.h); user_cache_dir("bakes") is where a front
// end keeps its bakes.
#include "bake/bake.h"
#include "bake/bake_key.h"
#include "bake/bake_writer.h"
#include "base/diagnostics.h"
#include "base/error.h"
#include "base/progress.h"
#include "io/cache_dir.h"
#include "settings/bake_settings.h"
