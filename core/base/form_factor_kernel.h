#pragma once
// Form-factor kernels: geometry of two small surfaces alone, shared by the
// clustering metric (patches/clustering.cpp) and the patch form factors
// (formfactor/form_factors.cpp explains where each is used). They sit in
// base/ because both modules stand on them and patches/ stands below
// formfactor/.
#include <algorithm>
#include <numbers>

#include <glm/glm.hpp>

namespace bounce {

struct SurfacePoint {
  glm::vec3 position;
  glm::vec3 normal;  // unit
  float area;
};

// Receivers closer than kNearFactor of their own sizes (sqrt of area) are
// integrated exactly; beyond, the differential kernel agrees with the exact
// form factor to ~1% (at 4 sizes furnace rows were off by up to 2.5%).
inline constexpr float kNearFactor = 6.0f;

// Exact form factor from a differential area at p (normal n) to the planar
// polygon `poly` (any winding), counting only the part above p's horizon
// (Lambert's contour integral). Never above 1.
float point_to_polygon_form_factor(const glm::vec3& p, const glm::vec3& n, const glm::vec3* poly,
                                   int count);

// Energy exchanged between two points standing for small areas, G = A_i F_ij
// = A_j F_ji, with the disk bound: a receiver of area A seen head-on from
// distance r subtends exactly A / (pi r^2 + A), so
//   G = A_i A_j cos_i cos_j / (pi r^2 + (A_i + A_j) / 2),
// symmetric and bounded as r -> 0. Used where a cheap, stable estimate is
// enough (the clustering metric); zero when the points do not face each other.
inline float bounded_exchange(const SurfacePoint& a, const SurfacePoint& b) {
  const glm::vec3 d = b.position - a.position;
  const float r2 = glm::dot(d, d);
  const float fa = glm::dot(a.normal, d), fb = -glm::dot(b.normal, d);
  if (fa <= 0.0f || fb <= 0.0f || !(r2 > 0.0f)) return 0.0f;
  return a.area * b.area * (fa * fb / r2) /
         (std::numbers::pi_v<float> * r2 + 0.5f * (a.area + b.area));
}

}  // namespace bounce
