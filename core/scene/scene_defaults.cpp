#include "scene/scene_defaults.h"

#include <algorithm>
#include <cmath>

namespace bounce::scene_internal {

Light default_light(const Bounds& bounds) {
  const glm::vec3 c = bounds.center();
  const glm::vec3 e = bounds.extent();
  Light light;
  light.type = Light::Type::Point;
  light.name = "default-light";
  light.position = glm::vec3(c.x, bounds.lo.y + 0.8f * e.y, c.z);
  light.color = glm::vec3(1.0f);
  light.intensity = glm::dot(e, e);
  return light;
}

Camera default_camera(const Bounds& bounds) {
  const glm::vec3 c = bounds.center();
  // A flat or point-like scene still needs the camera off the target.
  const float radius = std::max(0.5f * glm::length(bounds.extent()), 1e-6f);
  const float half_fov = glm::radians(0.5f * kDefaultFovYDeg);
  Camera camera;
  camera.target = c;
  camera.position = c + glm::vec3(0.0f, 0.0f, radius / std::sin(half_fov));
  camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
  camera.fov_y_deg = kDefaultFovYDeg;
  return camera;
}

}  // namespace bounce::scene_internal
