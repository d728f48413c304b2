#pragma once
// A bake's lit mesh written as a binary glTF, as `bounce bake --export-glb`
// exports it: the scene's own triangles lit from the bake by the lighting
// session's rule (bounce/relight.h), with their materials and textures.
#include <filesystem>

#include "bounce/relight.h"
#include "bounce/scene.h"

namespace bounce::cli {

// Reads the bake folder `folder` of `scene`, lights it with the scene's own
// lights and writes the lit mesh with its materials and textures to `glb`
// (written to a temporary name and renamed). Returns the file's exposure.
// Throws bounce::Error naming the file at fault.
float export_bake_glb(const std::filesystem::path& folder, const Scene& scene,
                      const std::filesystem::path& glb, Progress& progress);

}  // namespace bounce::cli
