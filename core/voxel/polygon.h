#pragma once
// Small planar-polygon helpers (convex polygons of a few vertices).
#include <vector>

#include <glm/glm.hpp>

namespace bounce {

// Keeps the part of the convex polygon where dot(normal, x) <= offset.
inline std::vector<glm::vec3> clip_polygon(const std::vector<glm::vec3>& poly,
                                           const glm::vec3& normal, float offset) {
  std::vector<glm::vec3> out;
  const std::size_t n = poly.size();
  for (std::size_t k = 0; k < n; ++k) {
    const glm::vec3& a = poly[k];
    const glm::vec3& b = poly[(k + 1) % n];
    const float da = glm::dot(normal, a) - offset, db = glm::dot(normal, b) - offset;
    if (da <= 0.0f) out.push_back(a);
    if ((da <= 0.0f) != (db <= 0.0f)) out.push_back(a + (da / (da - db)) * (b - a));
  }
  return out;
}

inline float polygon_area(const std::vector<glm::vec3>& poly) {
  if (poly.size() < 3) return 0.0f;
  glm::dvec3 sum(0.0);
  for (std::size_t k = 1; k + 1 < poly.size(); ++k)
    sum += glm::cross(glm::dvec3(poly[k] - poly[0]), glm::dvec3(poly[k + 1] - poly[0]));
  return static_cast<float>(0.5 * glm::length(sum));
}

// Area centroid (not the vertex average, which leans toward clustered or
// repeated vertices).
inline glm::vec3 polygon_centroid(const glm::vec3* poly, std::size_t count) {
  glm::dvec3 sum(0.0), mean(0.0);
  double total = 0.0;
  for (std::size_t k = 0; k < count; ++k) mean += glm::dvec3(poly[k]);
  mean /= static_cast<double>(count);
  for (std::size_t k = 1; k + 1 < count; ++k) {
    const glm::dvec3 a(poly[0]), b(poly[k]), c(poly[k + 1]);
    const double w = 0.5 * glm::length(glm::cross(b - a, c - a));
    sum += w * (a + b + c) / 3.0;
    total += w;
  }
  return glm::vec3(total > 0.0 ? sum / total : mean);
}

}  // namespace bounce
