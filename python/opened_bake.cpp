#include "opened_bake.h"

namespace fs = std::filesystem;

namespace bounce::python {

namespace {

fs::path baked_scene_path(const LoadedBake& bake, const fs::path& given) {
  if (!given.empty()) return given;
  const fs::path path = bake.manifest.at("scene").at("path").get<std::string>();
  if (!fs::exists(path))
    throw Error(path.string(), "the baked scene is not there any more (give it with scene=PATH)");
  return path;
}

Scene load_matching_scene(const LoadedBake& bake, const fs::path& path) {
  Diagnostics diagnostics;
  Scene scene = SceneLoader(diagnostics).load(path);
  const auto baked = bake.manifest.at("scene").at("triangles").get<std::size_t>();
  if (scene.triangle_count() != baked)
    throw Error(path.string(), "has " + std::to_string(scene.triangle_count()) +
                                   " triangles, the bake was made from " + std::to_string(baked) +
                                   ": not the same scene");
  return scene;
}

}  // namespace

OpenedBake::OpenedBake(const fs::path& folder, const fs::path& scene)
    : folder_(folder),
      bake_(BakeReader::read(folder, BakeReader::Dense::kIfNotCompressed)),
      scene_(load_matching_scene(bake_, baked_scene_path(bake_, scene))),
      tracer_(std::make_unique<RayTracer>(scene_)),
      gather_(read_final_gather(folder, bake_.size(), bake_.samples.samples.size())) {
  RelighterSettings settings;
  // A gather with sample sources reads each sample's direct irradiance.
  settings.frame.sample_irradiance = gather_ && gather_->samples > 0;
  relighter_ = std::make_unique<Relighter>(*tracer_, bake_.samples, bake_.patches,
                                           stored_transport(bake_), settings);
}

const LitMesh& OpenedBake::mesh() {
  if (!mesh_) {
    const TransferGrid grid = TransferGrid::from_manifest(bake_.manifest);
    if (gather_) {
      mesh_ = build_transfer_mesh(scene_, grid, TransferSettings{});
      if (mesh_->positions.size() != gather_->points())
        throw Error((folder_ / bake_file::kGatherFirst).string(),
                    "holds " + std::to_string(gather_->points()) +
                        " vertices, the scene's lit mesh has " +
                        std::to_string(mesh_->positions.size()) + ": not this scene");
    } else {
      // The patches' light lands on the mesh in relight(); the geometry alone
      // is the same for any light.
      mesh_ = transfer_to_mesh(*tracer_, bake_.patches.patches, grid,
                               std::vector<glm::vec3>(bake_.size(), glm::vec3(0.0f)),
                               TransferSettings{});
    }
  }
  return *mesh_;
}

RelitFrame OpenedBake::relight(const std::map<std::string, glm::vec3>& moved) {
  std::vector<Light> lights = scene_.lights;
  for (const auto& [name, position] : moved) {
    Light* found = nullptr;
    for (Light& l : lights)
      if (l.name == name) found = &l;
    if (!found) throw Error("lights", "the scene has no light named '" + name + "'");
    if (found->type == Light::Type::Directional)
      throw Error("lights", "'" + name + "' is a directional light: it has no position");
    found->position = position;
  }
  const std::vector<AreaLight> area = area_lights(scene_);
  relighter_->light(lights, area);
  const RuntimeFrame& frame = relighter_->frame();
  RelitFrame out;
  out.first_hit = frame.first_hit();
  out.indirect = frame.indirect();
  relighter_->reflected(out.reflected);
  out.exitance = frame.exitance();
  if (gather_) {
    LitMesh lit = mesh();
    std::vector<glm::vec3> gathered;
    relighter_->gather(*gather_, gathered);
    light_vertices(*tracer_, lights, area, gathered, lit);
    out.vertex_light = std::move(lit.radiosity);
  } else {
    const TransferGrid grid = TransferGrid::from_manifest(bake_.manifest);
    out.vertex_light =
        transfer_to_mesh(*tracer_, bake_.patches.patches, grid, out.exitance, TransferSettings{})
            .radiosity;
  }
  return out;
}

CameraImages OpenedBake::camera_images(const CameraImageSettings& settings, int gather_rays) {
  if (gather_rays < 0 || gather_rays > 65536)
    throw Error("gather_rays", "must be between 0 and 65536, got " + std::to_string(gather_rays));
  relighter_->light(scene_.lights, area_lights(scene_));
  const RuntimeFrame& frame = relighter_->frame();
  const std::vector<glm::vec3>& first_hit = frame.first_hit();
  const std::vector<glm::vec3>& indirect = frame.indirect();
  if (gather_rays > 0 && camera_gather_possible(bake_))
    return CameraGather(*tracer_, bake_, settings, gather_rays)
        .images(first_hit, indirect, frame.sample_irradiance(), scene_.lights, area_lights(scene_));
  const PatchGather nearest(bake_.patches.patches, indirect,
                            TransferGrid::from_manifest(bake_.manifest), tracer_.get(),
                            GatherSettings{});
  return render_camera(*tracer_, nearest, settings);
}

}  // namespace bounce::python
