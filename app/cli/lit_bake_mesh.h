#pragma once
// The scene's own triangles lit from a bake, as `bounce solve` writes them
// (lit.ply, lit.glb) and `bounce bake --export-glb` exports them: with the
// bake's final gather each vertex takes its own direct light plus albedo x
// the irradiance it gathers from the patches' reflected light; without one,
// the light the nearest patches send out.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bounce/bake_folder.h"
#include "bounce/relight.h"
#include "bounce/scene.h"

namespace bounce::cli {

// The lit mesh after relighter.light(): `folder` is the bake's (it names a
// gather that does not fit), `area` the area lights the frame used. With
// `product_seconds`, the per-frame part of the final gather runs five times
// and the best time of its sparse product is stored there, and in
// `near_seconds` the best time of lighting its near sources.
LitMesh light_bake_mesh(const RayTracer& tracer, const LoadedBake& bake, const std::string& folder,
                        const Relighter& relighter, const std::vector<AreaLight>& area,
                        const std::optional<FinalGather>& gather, Progress& progress,
                        double* product_seconds = nullptr, double* near_seconds = nullptr);

// Reads the bake folder `folder` of `scene`, lights it with the scene's own
// lights and writes the lit mesh with its materials and textures to `glb`
// (written to a temporary name and renamed). Returns the file's exposure.
// Throws bounce::Error naming the file at fault.
float export_bake_glb(const std::filesystem::path& folder, const Scene& scene,
                      const std::filesystem::path& glb, Progress& progress);

}  // namespace bounce::cli
