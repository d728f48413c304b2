#pragma once
// The form factor from a differential surface element to a triangle, in
// closed form: F = (1 / pi) x integral over the triangle of
// cos_p cos_l / r^2 dA, so a Lambertian emitter of exitance M lights the
// element with irradiance M x F. Lambert's contour integral (Baum, Rushmeier
// and Winget 1989, "Improving radiosity solutions through the use of
// analytically determined form-factors"): the triangle is first clipped to
// the element's upper half-space, since the part behind the element
// receives nothing.
#include <glm/glm.hpp>

namespace bounce {

// Element at `p` with unit normal `n`; triangle v0, v0 + e1, v0 + e2 with
// unit normal `normal` on its emitting side (`two_sided`: both). 0 when the
// element sees only the triangle's back or lies behind its own plane.
// `visible_point` (if given, and the result is not 0): a point inside the
// part of the triangle in front of the element (its corners' mean).
double triangle_form_factor(const glm::vec3& p, const glm::vec3& n, const glm::vec3& v0,
                            const glm::vec3& e1, const glm::vec3& e2, const glm::vec3& normal,
                            bool two_sided, glm::vec3* visible_point = nullptr);

}  // namespace bounce
