#include "preview_object_mesh.h"

#include <algorithm>

#include "bounce/error.h"
#include "bounce/scene.h"

namespace bounce::views {

ObjectMesh load_object_mesh(const std::string& path) {
  Diagnostics diagnostics;
  const Scene scene = SceneLoader(diagnostics).load(path);
  const Bounds b = scene.bounds();
  const glm::vec3 centre = 0.5f * (b.lo + b.hi);
  float radius = 0.0f;
  for (const glm::vec3& p : scene.positions) radius = std::max(radius, glm::length(p - centre));
  ObjectMesh mesh;
  mesh.name = scene.name;
  for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
    const glm::vec3 cross = scene.triangle_cross(t);
    if (!(glm::length(cross) > 0.0f)) continue;
    const glm::vec3 n = glm::normalize(cross);
    for (int k = 0; k < 3; ++k) {
      mesh.corners.push_back((scene.vertex(t, k) - centre) / radius);
      mesh.normals.push_back(n);
    }
  }
  if (mesh.corners.empty() || !(radius > 0.0f))
    throw Error(path, "holds no triangle with an area to draw");
  return mesh;
}

}  // namespace bounce::views
