#pragma once
// What the views show of a bake still running: the data a stage of the core's
// Baker has made so far (Baker::voxel_grid before the bake, then each stage's
// BakeResult through Baker::set_stage_done), in the shape of a bake folder
// read back (bake_view_data.h), so the same views draw it. The finished bake
// is then shown from its folder as always.
#include <memory>

#include "bake_view_data.h"
#include "bounce/bake.h"

namespace bounce::views {

// The voxels of `partial` (with their sample and patch counts once the
// stages that make them ran) and its patches with their samples once the
// patch stage ran; no matrices. The manifest holds what the views read of
// one: "grid", "scene" (name, path, lights) and "partial": true.
std::shared_ptr<const BakeViewData> partial_view_data(std::shared_ptr<const Scene> scene,
                                                      const BakeResult& partial);

}  // namespace bounce::views
