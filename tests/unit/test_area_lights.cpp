// Area lights (emissive triangles) against the closed-form irradiance of a
// Lambertian square on the axis of a point below it, with and without an
// occluder.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "base/form_factor_kernel.h"
#include "raytrace/ray_tracer.h"
#include "runtime/area_lights.h"
#include "test_scenes.h"

namespace bounce {
namespace {

// Form factor from a differential area to an X x Y rectangle parallel to it
// at unit height, the differential area below one corner (Howell's catalogue,
// configuration B-3).
double corner_form_factor(double x, double y) {
  const double a = std::sqrt(1 + x * x), b = std::sqrt(1 + y * y);
  return (x / a * std::atan(y / a) + y / b * std::atan(x / b)) / (2 * std::numbers::pi);
}

TEST(AreaLights, SquareEmitterMatchesTheClosedFormIrradiance) {
  // Unit square emitter at z = 1 facing down (-z), exitance (2, 1, 0.5); the
  // receiver point at the origin below its centre, facing up. Its four
  // quarters are 0.5 x 0.5 rectangles with a corner above the point.
  Scene s;
  test_scenes::add_quad(s, "light", {-0.5f, -0.5f, 1}, {-0.5f, 0.5f, 1}, {0.5f, 0.5f, 1},
                        {0.5f, -0.5f, 1}, glm::vec3(0.5f), glm::vec3(2.0f, 1.0f, 0.5f));
  test_scenes::add_quad(s, "floor", {-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0});
  const RayTracer tracer(s);
  const std::vector<AreaLight> lights = area_lights(s);
  ASSERT_EQ(lights.size(), 2u) << "the emitter's two triangles";
  EXPECT_NEAR(lights[0].normal.z, -1.0f, 1e-6f);
  const double expected = 4 * corner_form_factor(0.5, 0.5);  // E / M
  glm::dvec3 e(0.0);
  for (const AreaLight& l : lights)
    e += glm::dvec3(area_light_irradiance(tracer, {0, 0, 0}, {0, 0, 1}, l, 32, 7));
  // 1024 stratified samples per triangle: well under 1% here.
  EXPECT_NEAR(e.x / 2.0, expected, 0.01 * expected);
  EXPECT_NEAR(e.y / 1.0, expected, 0.01 * expected);
  EXPECT_NEAR(e.z / 0.5, expected, 0.01 * expected);
  // The back of a one-sided emitter gives nothing, nor does a point facing away.
  for (const AreaLight& l : lights) {
    EXPECT_EQ(area_light_irradiance(tracer, {0, 0, 2}, {0, 0, -1}, l, 8, 7), glm::vec3(0.0f));
    EXPECT_EQ(area_light_irradiance(tracer, {0, 0, 0}, {0, 0, -1}, l, 8, 7), glm::vec3(0.0f));
  }
}

TEST(AreaLights, AnOccluderCastsASoftShadow) {
  // A blocker covering the x > 0 half of the view of the emitter: half the light.
  Scene s;
  test_scenes::add_quad(s, "light", {-0.5f, -0.5f, 1}, {-0.5f, 0.5f, 1}, {0.5f, 0.5f, 1},
                        {0.5f, -0.5f, 1}, glm::vec3(0.5f), glm::vec3(1.0f));
  test_scenes::add_quad(s, "blocker", {0, -1, 0.5f}, {0, 1, 0.5f}, {1, 1, 0.5f}, {1, -1, 0.5f});
  const RayTracer tracer(s);
  double e = 0.0;
  for (const AreaLight& l : area_lights(s))
    e += area_light_irradiance(tracer, {0, 0, 0}, {0, 0, 1}, l, 32, 7).x;
  const double full = 4 * corner_form_factor(0.5, 0.5);
  EXPECT_NEAR(e, 0.5 * full, 0.02 * full);
}

// The closed form an untextured emitter is lit with
// (point_to_polygon_form_factor), and its sides: without occluders every
// shadow ray reaches the emitter, so the light is the exitance times it.
TEST(AreaLights, UnoccludedLightIsTheClosedFormAndClipsAtTheHorizon) {
  // The unit square of the first test: the catalogue's value.
  const glm::vec3 square[4] = {
      {-0.5f, -0.5f, 1}, {0.5f, -0.5f, 1}, {0.5f, 0.5f, 1}, {-0.5f, 0.5f, 1}};
  const glm::vec3 p(0, 0, 0), up(0, 0, 1);
  EXPECT_NEAR(point_to_polygon_form_factor(p, up, square, 4), 4 * corner_form_factor(0.5, 0.5),
              1e-6);
  // Behind a one-sided emitter: nothing; two-sided: the same from behind.
  Scene s;
  test_scenes::add_quad(s, "light", square[0], square[3], square[2], square[1], glm::vec3(0.5f),
                        glm::vec3(1.0f));
  test_scenes::add_quad(s, "floor", {-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0});
  const RayTracer tracer(s);
  std::vector<AreaLight> lights = area_lights(s);
  const auto light_at = [&tracer, &lights](const glm::vec3& at, const glm::vec3& n) {
    double e = 0.0;
    for (const AreaLight& l : lights) e += area_light_irradiance(tracer, at, n, l, 2, 7).x;
    return e;
  };
  EXPECT_EQ(light_at({0, 0, 2}, -up), 0.0);
  const double front = light_at(p, up);
  for (AreaLight& l : lights) l.two_sided = true;
  EXPECT_NEAR(light_at({0, 0, 2}, -up), front, 1e-6);
  // A receiver tilted so that its plane cuts the square: only the part in
  // front of it counts. Against the whole emitter sampled densely, with
  // each sample's cosine clamped at the horizon (1024 x 1024 midpoints).
  const glm::vec3 tilted = glm::normalize(glm::vec3(1, 0, 0.3f));
  double sum = 0.0;
  constexpr int kN = 1024;
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j) {
      const glm::dvec3 q(-0.5 + (i + 0.5) / kN, -0.5 + (j + 0.5) / kN, 1.0);
      const double r2 = glm::dot(q, q);
      const double cos_p = std::max(0.0, glm::dot(glm::dvec3(tilted), q) / std::sqrt(r2));
      sum += cos_p * (1.0 / std::sqrt(r2)) / r2;
    }
  const double expected = sum / (double(kN) * kN) / std::numbers::pi;
  EXPECT_NEAR(point_to_polygon_form_factor(p, tilted, square, 4), expected, 1e-4 * expected);
}

}  // namespace
}  // namespace bounce
