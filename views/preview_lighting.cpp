#include "preview_lighting.h"

#include <chrono>

#include "bounce/relight.h"
#include "bounce/scene.h"

namespace bounce::views {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// The product `bounce solve --multiply auto` picks on a machine without a
// GPU: the compressed matrix in C++, or the dense one for a dense bake. The
// preview reads b and T b from the published buffers, never the record.
LightingSessionSettings preview_settings() {
  LightingSessionSettings s;
  s.relighter.multiply = MultiplyChoice::kAutoCpu;
  s.relighter.frame.record = false;
  s.relighter.shadow_frames = PreviewLighting::kShadowFrames;
  return s;
}

}  // namespace

PreviewLighting::PreviewLighting(std::shared_ptr<const BakeViewData> data)
    : data_(std::move(data)) {
  if (!data_) throw Error("preview", "no bake loaded");
  if (!data_->scene)
    throw Error(data_->bake.dir.string(),
                "the scene it was baked from is not on disk any more: the preview needs it");
  const Scene& scene = *data_->scene;
  bool found = false;
  for (const Light& l : scene.lights)
    if (l.type != Light::Type::Directional) {
      light_ = l;
      found = true;
      break;
    }
  if (!found) throw Error(scene.path, "has no point or spot light for the preview to move");
  // The bake is part of the studio's data: the session shares it.
  session_ = std::make_unique<LightingSession>(
      std::shared_ptr<const LoadedBake>(data_, &data_->bake), data_->scene, preview_settings());
  session_->use_lights({light_});
  geometry_ = &session_->mesh();
}

PreviewLighting::~PreviewLighting() = default;

PreviewLighting::Solve PreviewLighting::solve(const glm::vec3& light_position, bool settle,
                                              const std::optional<glm::vec3>& probes_at) {
  Solve s;
  s.light_position = light_position;
  session_->move_light(light_.name, light_position);
  do {
    auto t = Clock::now();
    session_->light();
    s.frame_seconds = since(t);
    t = Clock::now();
    // The irradiance each vertex receives: the shaders reflect it with the
    // albedo under each pixel and add the direct light themselves.
    session_->vertex_irradiance(s.vertex_irradiance);
    s.transfer_seconds = since(t);
    s.settled = session_->relighter().shadows_settled();
  } while (settle && !s.settled);
  if (probes_at) solve_probes(*probes_at, s);
  return s;
}

void PreviewLighting::solve_probes(const glm::vec3& sphere_position, Solve& s) {
  s.sphere_position = sphere_position;
  if (!has_probes()) return;
  const auto t = Clock::now();
  session_->probe_sh(s.probe_sh);
  s.sphere_sh = sh_at(sphere_position);
  s.probe_seconds = since(t);
  s.probes_solved = true;
}

const std::vector<glm::vec3>& PreviewLighting::probe_positions() const {
  static const std::vector<glm::vec3> none;
  return has_probes() ? session_->light_probes()->position : none;
}

std::array<glm::vec3, kShCoefficients> PreviewLighting::sh_at(const glm::vec3& point) {
  std::array<glm::vec3, kShCoefficients> sh{};
  if (has_probes()) session_->probe_sh_at(point, sh);
  return sh;
}

float PreviewLighting::cell_size() const { return session_->description().grid.cell_size; }

LitMesh PreviewLighting::lit_mesh(const glm::vec3& light_position) {
  // Settled first: the lit mesh gathers with the near sources' shadows.
  solve(light_position, true);
  return session_->lit_mesh();
}

}  // namespace bounce::views
