#include "opened_bake.h"

namespace fs = std::filesystem;

namespace bounce::python {

namespace {

LightingSessionSettings settings_for(const fs::path& scene) {
  LightingSessionSettings s;
  s.scene = scene;
  return s;
}

}  // namespace

OpenedBake::OpenedBake(const fs::path& folder, const fs::path& scene)
    : session_(folder, settings_for(scene)) {}

RelitFrame OpenedBake::relight(const std::map<std::string, glm::vec3>& moved) {
  session_.reset_lights();
  for (const auto& [name, position] : moved) session_.move_light(name, position);
  session_.light();
  lit_ = true;
  const RuntimeFrame& frame = session_.frame();
  RelitFrame out;
  out.first_hit = frame.first_hit();
  out.indirect = frame.indirect();
  session_.relighter().reflected(out.reflected);
  out.exitance = frame.exitance();
  out.vertex_light = session_.lit_mesh().radiosity;
  session_.probe_sh(out.probe_sh);
  return out;
}

CameraImages OpenedBake::camera_images(const CameraImageSettings& settings, int gather_rays) {
  session_.reset_lights();
  session_.light();
  lit_ = true;
  return session_.camera(settings, gather_rays).images();
}

std::array<glm::vec3, kShCoefficients> OpenedBake::probe_sh_at(const glm::vec3& point) {
  if (!lit_) {
    session_.reset_lights();
    session_.light();
    lit_ = true;
  }
  std::array<glm::vec3, kShCoefficients> sh;
  session_.probe_sh_at(point, sh);
  return sh;
}

}  // namespace bounce::python
