#include "formfactor/kernel.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace bounce {

float point_to_polygon_form_factor(const glm::vec3& p, const glm::vec3& n, const glm::vec3* poly,
                                   int count) {
  // Clip against the horizon plane n.(x - p) >= 0 (Sutherland-Hodgman).
  constexpr int kMax = 16;
  glm::vec3 clipped[kMax];
  int m = 0;
  for (int k = 0; k < count && m < kMax - 1; ++k) {
    const glm::vec3& a = poly[k];
    const glm::vec3& b = poly[(k + 1) % count];
    const float da = glm::dot(n, a - p), db = glm::dot(n, b - p);
    if (da >= 0.0f) clipped[m++] = a - p;
    if ((da >= 0.0f) != (db >= 0.0f)) clipped[m++] = a + (da / (da - db)) * (b - a) - p;
  }
  if (m < 3) return 0.0f;
  // Lambert: F = 1/(2 pi) | sum_k gamma_k n . (R_k x R_k+1) / |R_k x R_k+1| |.
  double sum = 0.0;
  for (int k = 0; k < m; ++k) {
    const glm::dvec3 r0 = glm::normalize(glm::dvec3(clipped[k]));
    const glm::dvec3 r1 = glm::normalize(glm::dvec3(clipped[(k + 1) % m]));
    const glm::dvec3 c = glm::cross(r0, r1);
    const double len = glm::length(c);
    if (len < 1e-15) continue;
    const double gamma = std::atan2(len, glm::dot(r0, r1));
    sum += gamma * glm::dot(glm::dvec3(n), c) / len;
  }
  return static_cast<float>(std::min(1.0, std::abs(sum) / (2.0 * std::numbers::pi)));
}

void footprint_square(const glm::vec3& c, const glm::vec3& n, float area, glm::vec3 out[4]) {
  // Tangent: the world axis least aligned with n, projected into the plane.
  const glm::vec3 a = glm::abs(n);
  const glm::vec3 axis = a.x <= a.y && a.x <= a.z ? glm::vec3(1, 0, 0)
                         : a.y <= a.z             ? glm::vec3(0, 1, 0)
                                                  : glm::vec3(0, 0, 1);
  const glm::vec3 t = glm::normalize(axis - glm::dot(axis, n) * n);
  const glm::vec3 b = glm::cross(n, t);
  const float h = 0.5f * std::sqrt(area);
  out[0] = c - h * t - h * b;
  out[1] = c + h * t - h * b;
  out[2] = c + h * t + h * b;
  out[3] = c - h * t + h * b;
}

float exchange(const SurfacePoint& a, const SurfacePoint& b) {
  const glm::vec3 d = b.position - a.position;
  const float r2 = glm::dot(d, d);
  // Facing test on the centres: each must be in front of the other's plane.
  const float fa = glm::dot(a.normal, d), fb = -glm::dot(b.normal, d);
  if (fa <= 0.0f || fb <= 0.0f) return 0.0f;
  const float near2 = kNearFactor * kNearFactor * std::max(a.area, b.area);
  if (r2 >= near2) return a.area * b.area * fa * fb / (std::numbers::pi_v<float> * r2 * r2);
  glm::vec3 sq[4];
  footprint_square(b.position, b.normal, b.area, sq);
  const float ab = point_to_polygon_form_factor(a.position, a.normal, sq, 4);
  footprint_square(a.position, a.normal, a.area, sq);
  const float ba = point_to_polygon_form_factor(b.position, b.normal, sq, 4);
  return 0.5f * (a.area * ab + b.area * ba);
}

}  // namespace bounce
