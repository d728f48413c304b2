// The preview's orbit camera against hand-computed positions and pixels.
#include <gtest/gtest.h>

#include <cmath>

#include "orbit_camera.h"

namespace bounce::views {

namespace {

OrbitCamera camera_at_five() {
  Camera scene_camera;
  scene_camera.position = {0.0f, 0.0f, 5.0f};
  scene_camera.target = {0.0f, 0.0f, 0.0f};
  scene_camera.up = {0.0f, 2.0f, 0.0f};  // not unit: normalised
  scene_camera.fov_y_deg = 90.0f;
  OrbitCamera c;
  c.reset(scene_camera, 2.0f);
  return c;
}

void expect_near(const glm::vec3& a, const glm::vec3& b) {
  EXPECT_NEAR(a.x, b.x, 1e-4f);
  EXPECT_NEAR(a.y, b.y, 1e-4f);
  EXPECT_NEAR(a.z, b.z, 1e-4f);
}

}  // namespace

TEST(OrbitCamera, StartsAsTheSceneCameraWithItsTargetAtTheImageCentre) {
  const OrbitCamera c = camera_at_five();
  expect_near(c.eye(), {0.0f, 0.0f, 5.0f});
  const glm::vec2 centre = c.project({0.0f, 0.0f, 0.0f}, 200, 100);
  EXPECT_NEAR(centre.x, 100.0f, 1e-3f);
  EXPECT_NEAR(centre.y, 50.0f, 1e-3f);
  // 90 degrees of view: at depth 5 the image's half-height is 5 units, so a
  // point 2.5 units up lands a quarter of the height above the centre.
  EXPECT_NEAR(c.project({0.0f, 2.5f, 0.0f}, 200, 100).y, 25.0f, 1e-3f);
  EXPECT_NEAR(c.pixel_size_at({0.0f, 0.0f, 0.0f}, 100), 0.1f, 1e-5f);
  expect_near(c.right_axis(), {1.0f, 0.0f, 0.0f});
  expect_near(c.up_axis(), {0.0f, 1.0f, 0.0f});
}

TEST(OrbitCamera, AQuarterTurnOfYawMovesTheEyeRoundTheTarget) {
  OrbitCamera c = camera_at_five();
  // 0.01 radians a pixel: -157.08 pixels turn the forward (0, 0, -1) by
  // +pi/2 about +y, to (-1, 0, 0), so the eye moves to +x.
  c.orbit(-50.0f * static_cast<float>(M_PI), 0.0f);
  expect_near(c.eye(), {5.0f, 0.0f, 0.0f});
  // Pitch stops at 1.5 radians, short of the pole.
  c.orbit(0.0f, -1e4f);
  EXPECT_NEAR(std::abs(c.eye().y), 5.0f * std::sin(1.5f), 1e-3f);
  EXPECT_NEAR(glm::length(c.eye()), 5.0f, 1e-3f);
}

TEST(OrbitCamera, DollyStaysWithinItsBounds) {
  OrbitCamera c = camera_at_five();
  c.dolly(1e6f);
  EXPECT_NEAR(glm::length(c.eye()), 20.0f * 2.0f, 1e-3f);
  c.dolly(1e-9f);
  EXPECT_NEAR(glm::length(c.eye()), 0.01f * 2.0f, 1e-5f);
}

}  // namespace bounce::views
