#include "runtime/final_gather.h"

#include <algorithm>
#include <cmath>

#include "base/error.h"
#include "runtime/direct_light.h"

namespace bounce {

std::vector<glm::vec3> gather_points_of_vertices(const std::vector<glm::vec3>& positions,
                                                 const std::vector<glm::uvec3>& triangles) {
  std::vector<glm::vec3> out = positions;
  std::vector<bool> moved(positions.size(), false);
  for (const glm::uvec3& t : triangles) {
    const glm::vec3 c = (positions[t.x] + positions[t.y] + positions[t.z]) / 3.0f;
    for (int k = 0; k < 3; ++k) {
      if (t[k] >= positions.size() || moved[t[k]]) continue;
      out[t[k]] = positions[t[k]] + 0.05f * (c - positions[t[k]]);
      moved[t[k]] = true;
    }
  }
  return out;
}

void light_vertices(const RayTracer& tracer, const std::vector<Light>& lights,
                    const std::vector<AreaLight>& area, const std::vector<glm::vec3>& gathered,
                    LitMesh& mesh) {
  const std::size_t n = mesh.positions.size();
  if (gathered.size() != n) throw Error("final gather", "one gathered value per vertex expected");
  const Scene& scene = tracer.scene();
  const std::vector<std::uint32_t> triangle = vertex_source_triangles(mesh);
  const std::vector<glm::vec3> at = gather_points_of_vertices(mesh.positions, mesh.triangles);
  mesh.radiosity.resize(n);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t vi = 0; vi < static_cast<std::int64_t>(n); ++vi) {
    const auto v = static_cast<std::size_t>(vi);
    const glm::vec3 direct =
        irradiance_at(tracer, at[v] + 10.0f * tracer.epsilon() * mesh.normals[v], mesh.normals[v],
                      lights, area, 4, v);
    mesh.radiosity[v] =
        scene.emission_at(triangle[v], mesh.positions[v]) +
        scene.flat_albedo_at(triangle[v], mesh.positions[v]) * (direct + gathered[v]);
  }
}

}  // namespace bounce
