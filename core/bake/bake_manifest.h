#pragma once
// A bake's manifest (docs/bake-format.md, "manifest.json"): what was asked
// and what was used, counts, timings, checks, the light probes' placement,
// warnings and what was left out. The folder's writer (bake/bake_writer.h)
// adds the list of files.
#include <nlohmann/json.hpp>

#include "bake/bake.h"

namespace bounce {

// The manifest without its "files" list.
nlohmann::json make_manifest(const Scene& scene, const BakeResult& result,
                             const Diagnostics& diagnostics);

// Which light probes the bake placed: the setting, with `auto` resolved by
// what the placement did (the result's settings keep `auto`, so that a
// re-bake compares what was asked). Off: the folder has no probe files.
ProbePlacementMode placed_probes(const BakeResult& result);

}  // namespace bounce
