#include "lit_bake_mesh.h"

#include <algorithm>
#include <chrono>

#include "bounce/export.h"

namespace bounce::cli {

LitMesh light_bake_mesh(const RayTracer& tracer, const LoadedBake& bake, const std::string& folder,
                        const Relighter& relighter, const std::vector<AreaLight>& area,
                        const std::optional<FinalGather>& gather, Progress& progress,
                        double* product_seconds, double* near_seconds) {
  const Scene& scene = tracer.scene();
  const TransferGrid grid = TransferGrid::from_manifest(bake.manifest);
  if (!gather) {
    // The mesh shows everything the patches send out: emission + b + T b.
    return transfer_to_mesh(tracer, bake.patches.patches, grid, relighter.frame().exitance(),
                            TransferSettings{}, &progress);
  }
  LitMesh mesh = build_transfer_mesh(scene, grid, TransferSettings{}, &progress);
  if (mesh.positions.size() != gather->points())
    throw Error((std::filesystem::path(folder) / bake_file::kGatherFirst).string(),
                "holds " + std::to_string(gather->points()) +
                    " vertices, the scene's lit mesh has " + std::to_string(mesh.positions.size()) +
                    ": not this scene");
  std::vector<glm::vec3> gathered;
  const int repeats = product_seconds != nullptr ? 5 : 1;
  double best = 1e30, best_near = 1e30;
  for (int rep = 0; rep < repeats; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
    relighter.gather(*gather, gathered);
    best = std::min(best,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    best_near = std::min(best_near, relighter.near_seconds());
  }
  // The product alone, without lighting the near sources.
  if (product_seconds != nullptr) *product_seconds = best - best_near;
  if (near_seconds != nullptr) *near_seconds = best_near;
  light_vertices(tracer, scene.lights, area, gathered, mesh);
  return mesh;
}

float export_bake_glb(const std::filesystem::path& folder, const Scene& scene,
                      const std::filesystem::path& glb, Progress& progress) {
  const LoadedBake bake = BakeReader::read(folder.string(), BakeReader::Dense::kIfNotCompressed);
  const RayTracer tracer(scene);
  const std::vector<AreaLight> area = area_lights(scene);
  Relighter relighter(tracer, bake.samples, bake.patches, stored_transport(bake));
  relighter.light(scene.lights, area);
  const std::optional<FinalGather> gather =
      read_final_gather(folder.string(), bake.size(), bake.samples.samples.size());
  const LitMesh mesh =
      light_bake_mesh(tracer, bake, folder.string(), relighter, area, gather, progress);
  return write_lit_scene_glb(glb, scene, mesh, scene.name);
}

}  // namespace bounce::cli
