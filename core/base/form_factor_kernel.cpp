#include "base/form_factor_kernel.h"

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

}  // namespace bounce
