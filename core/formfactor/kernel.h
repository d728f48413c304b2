#pragma once
// Energy exchanged between two surface samples: G_ij = A_i F_ij = A_j F_ji
// (symmetric, so reciprocity holds by construction; F_ij = G_ij / A_i).
//
// Far apart, the differential kernel is accurate:
//   G_ij = A_i A_j cos_i cos_j / (pi r^2).
// Close together it is singular (r -> 0) and point sampling it gives form
// factors above 1 near edges and corners (DESIGN.md section 6). There each
// sample is given its footprint, a square of its own area in its tangent
// plane, and the exact point-to-polygon form factor (Lambert's contour
// integral, the polygon clipped to the horizon of the point) is taken both
// ways and averaged:
//   G_ij = (A_i F(p_i -> square_j) + A_j F(p_j -> square_i)) / 2.
// Bounded: F(point -> polygon) <= 1 for any polygon. The switch happens at
// r^2 = kNearFactor^2 * max(A_i, A_j) (6 sides of the square: the two forms
// agree to ~1% there; at 4 sides furnace rows were off by up to 2.5%).
#include <glm/glm.hpp>

namespace bounce {

struct SurfacePoint {
  glm::vec3 position;
  glm::vec3 normal;  // unit
  float area;
};

inline constexpr float kNearFactor = 6.0f;

// Exact form factor from a differential area at p (normal n) to the planar
// polygon `poly` (any winding), counting only the part above p's horizon.
float point_to_polygon_form_factor(const glm::vec3& p, const glm::vec3& n, const glm::vec3* poly,
                                   int count);

// The footprint square of a sample: area `area`, centred at c, in the plane
// with normal n, edges along the tangents closest to the world axes (so that
// axis-aligned walls get axis-aligned footprints).
void footprint_square(const glm::vec3& c, const glm::vec3& n, float area, glm::vec3 out[4]);

// G_ij as above; zero when the two samples do not face each other.
float exchange(const SurfacePoint& a, const SurfacePoint& b);

}  // namespace bounce
