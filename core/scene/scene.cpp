#include "scene/scene.h"

namespace bounce {

glm::vec3 Scene::triangle_cross(std::size_t tri) const {
  const glm::vec3 a = vertex(tri, 0), b = vertex(tri, 1), c = vertex(tri, 2);
  return glm::cross(b - a, c - a);
}

float Scene::triangle_area(std::size_t tri) const {
  return 0.5f * glm::length(triangle_cross(tri));
}

const char* light_type_name(Light::Type type) {
  switch (type) {
    case Light::Type::Point:
      return "point";
    case Light::Type::Spot:
      return "spot";
    case Light::Type::Directional:
      return "directional";
  }
  return "unknown";
}

Bounds Scene::bounds() const {
  Bounds b;
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) b.extend(positions[t[k]]);
  return b;
}

}  // namespace bounce
