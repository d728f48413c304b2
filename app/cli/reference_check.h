#pragma once
// The bake measured against the path-traced reference (core/reference), for
// `bounce bake --reference` and `bounce report`: the indirect light a bake
// gives on the scene camera's picture, compared with the reference's.
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "bounce/bake.h"
#include "bounce/progress.h"
#include "bounce/relight.h"
#include "bounce/report.h"
#include "bounce/scene.h"

namespace bounce::cli {

// The bake's indirect picture (96 x 72) against a 256-path reference (cached
// in ReferenceCache::default_dir()), noise-corrected relative RMSE, with the
// run time of one light move: `update_ms` the direct light and T b,
// `gather_ms` the bake's gather to its lit mesh's vertices (0 without one),
// `light_move_ms` both. Returns the JSON summary; `line` gets one
// human-readable sentence.
nlohmann::json check_bake_against_reference(const Scene& scene, const BakeResult& bake,
                                            Progress& progress, std::string& line);

}  // namespace bounce::cli
