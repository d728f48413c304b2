#include "preview_lighting.h"

#include <chrono>

#include "bounce/bake_folder.h"
#include "bounce/relight.h"
#include "bounce/scene.h"

namespace bounce::views {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

}  // namespace

PreviewLighting::PreviewLighting(std::shared_ptr<const BakeViewData> data)
    : data_(std::move(data)) {
  if (!data_) throw Error("preview", "no bake loaded");
  const std::string where = data_->bake.dir.string();
  if (!data_->scene)
    throw Error(where, "the scene it was baked from is not on disk any more: the preview needs it");
  const Scene& scene = *data_->scene;
  bool found = false;
  for (const Light& l : scene.lights)
    if (l.type != Light::Type::Directional) {
      light_ = l;
      found = true;
      break;
    }
  if (!found) throw Error(scene.path, "has no point or spot light for the preview to move");
  lights_ = {light_};

  tracer_ = std::make_unique<RayTracer>(scene);
  // The product `bounce solve --multiply auto` picks on a machine without a
  // GPU: the compressed matrix in C++, or the dense one for a dense bake.
  const LoadedBake& bake = data_->bake;
  RelighterSettings relight;
  relight.multiply = MultiplyChoice::kAutoCpu;
  relight.frame.record = false;
  relighter_ = std::make_unique<Relighter>(*tracer_, bake.samples, bake.patches,
                                           stored_transport(bake), relight);

  gather_ = read_final_gather(bake.dir, bake.size(), bake.samples.samples.size());
  grid_ = TransferGrid::from_manifest(bake.manifest);
  geometry_ = build_transfer_mesh(scene, grid_, TransferSettings{});
  work_ = geometry_;
  if (gather_) {
    if (gather_->points() != geometry_.positions.size())
      throw Error((bake.dir / bake_file::kGatherFirst).string(),
                  "holds " + std::to_string(gather_->points()) +
                      " vertices, the scene's lit mesh "
                      "has " +
                      std::to_string(geometry_.positions.size()) + ": not this scene");
  } else {
    const std::vector<std::uint32_t> source = vertex_source_triangles(geometry_);
    for (std::size_t v = 0; v < source.size(); ++v) {
      const glm::vec3 albedo = scene.flat_albedo_at(source[v], geometry_.positions[v]);
      glm::vec3 inverse(0.0f);
      for (int c = 0; c < 3; ++c)
        if (albedo[c] > 1e-4f) inverse[c] = 1.0f / albedo[c];
      vertex_inverse_albedo_.push_back(inverse);
    }
  }
}

PreviewLighting::~PreviewLighting() = default;

PreviewLighting::Solve PreviewLighting::solve(const glm::vec3& light_position) {
  Solve s;
  s.light_position = light_position;
  lights_.front().position = light_position;
  auto t = Clock::now();
  relighter_->light(lights_);
  s.frame_seconds = since(t);
  t = Clock::now();
  if (gather_) {
    // The bake's final gather: each vertex sums the reflected light b + T b
    // of the patches it sees, the irradiance it receives (the shaders
    // reflect it with the albedo under each pixel and add the direct light
    // themselves).
    relighter_->gather(*gather_, s.vertex_irradiance);
  } else {
    // Without one, the nearest patches' T b (the camera of `bounce solve`
    // does the same), turned back into irradiance.
    const PatchGather gather(data_->bake.patches.patches, relighter_->frame().indirect(), grid_,
                             tracer_.get(), GatherSettings{});
    relight(work_, gather);
    s.vertex_irradiance = work_.radiosity;
    for (std::size_t v = 0; v < s.vertex_irradiance.size(); ++v)
      s.vertex_irradiance[v] *= vertex_inverse_albedo_[v];
  }
  s.transfer_seconds = since(t);
  return s;
}

LitMesh PreviewLighting::lit_mesh(const glm::vec3& light_position) {
  lights_.front().position = light_position;
  relighter_->light(lights_);
  LitMesh mesh = geometry_;
  if (gather_) {
    std::vector<glm::vec3> gathered;
    relighter_->gather(*gather_, gathered);
    light_vertices(*tracer_, lights_, {}, gathered, mesh);
  } else {
    std::vector<glm::vec3> exitance;
    relighter_->reflected(exitance);
    const std::vector<Patch>& patches = data_->bake.patches.patches;
    for (std::size_t p = 0; p < exitance.size(); ++p) exitance[p] += patches[p].emission;
    const PatchGather gather(patches, exitance, grid_, tracer_.get(), GatherSettings{});
    relight(mesh, gather);
  }
  return mesh;
}

}  // namespace bounce::views
