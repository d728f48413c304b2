#include "lit_bake_mesh.h"

#include <memory>

#include "bounce/bake_folder.h"
#include "bounce/export.h"

namespace bounce::cli {

float export_bake_glb(const std::filesystem::path& folder, const Scene& scene,
                      const std::filesystem::path& glb, Progress& progress) {
  auto bake = std::make_shared<const LoadedBake>(
      BakeReader::read(folder, BakeReader::Dense::kIfNotCompressed));
  // The caller keeps the scene alive for the whole call: shared without owning.
  const std::shared_ptr<const Scene> shared(std::shared_ptr<const Scene>{}, &scene);
  LightingSession session(std::move(bake), shared);
  session.light();
  const LitMesh mesh = session.lit_mesh(&progress);
  return write_lit_scene_glb(glb, scene, mesh, scene.name);
}

}  // namespace bounce::cli
