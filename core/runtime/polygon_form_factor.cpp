#include "runtime/polygon_form_factor.h"

#include <array>
#include <cmath>
#include <numbers>

namespace bounce {

namespace {

// The triangle relative to p, clipped to the half-space n . x >= 0
// (Sutherland-Hodgman against one plane: at most 4 vertices).
int clip_to_upper_half_space(const std::array<glm::dvec3, 3>& tri, const glm::dvec3& n,
                             std::array<glm::dvec3, 4>& out) {
  int count = 0;
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3& a = tri[k];
    const glm::dvec3& b = tri[(k + 1) % 3];
    const double ha = glm::dot(n, a), hb = glm::dot(n, b);
    if (ha >= 0.0) out[count++] = a;
    if ((ha >= 0.0) != (hb >= 0.0)) out[count++] = a + (b - a) * (ha / (ha - hb));
  }
  return count;
}

}  // namespace

double triangle_form_factor(const glm::vec3& p, const glm::vec3& n, const glm::vec3& v0,
                            const glm::vec3& e1, const glm::vec3& e2, const glm::vec3& normal,
                            bool two_sided, glm::vec3* visible_point) {
  // A planar emitter shows p one side only.
  const float side = glm::dot(normal, p - v0);
  if (!(side > 0.0f) && !(two_sided && side < 0.0f)) return 0.0;
  const glm::dvec3 a = glm::dvec3(v0) - glm::dvec3(p);
  const std::array<glm::dvec3, 3> tri{a, a + glm::dvec3(e1), a + glm::dvec3(e2)};
  std::array<glm::dvec3, 4> poly;
  const glm::dvec3 nd(n);
  const int count = clip_to_upper_half_space(tri, nd, poly);
  if (count < 3) return 0.0;
  // Each edge subtends angle theta in the plane through p and the edge, whose
  // unit normal is the cross product's direction: the edge contributes
  // theta x (n . that normal). atan2 keeps theta exact for short edges,
  // where acos of a dot product near 1 would lose half its digits.
  double sum = 0.0;
  glm::dvec3 corners(0.0);
  for (int k = 0; k < count; ++k) {
    corners += poly[k];
    const glm::dvec3& u = poly[k];
    const glm::dvec3& w = poly[(k + 1) % count];
    const glm::dvec3 c = glm::cross(u, w);
    const double s = glm::length(c);
    if (!(s > 0.0)) continue;
    sum += std::atan2(s, glm::dot(u, w)) * glm::dot(nd, c) / s;
  }
  if (visible_point) *visible_point = glm::vec3(glm::dvec3(p) + corners / double(count));
  return std::abs(sum) / (2.0 * std::numbers::pi);
}

}  // namespace bounce
