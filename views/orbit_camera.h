#pragma once
// The preview's camera: it starts as the scene's camera and orbits its
// target. Left drag turns it (yaw about the scene's up, pitch about the
// camera's right axis), right drag or the wheel moves it closer or farther,
// within 0.01 to 20 scene diagonals.
#include <glm/glm.hpp>

#include "bounce/scene.h"

namespace bounce::views {

class OrbitCamera {
 public:
  // Back to the scene's camera; `diagonal`: the scene's bounding-box
  // diagonal, which scales distances and depth ranges.
  void reset(const Camera& camera, float diagonal);

  glm::vec3 eye() const;
  glm::vec3 target() const { return target_; }
  glm::vec3 up() const { return up_; }
  float fov_y_deg() const { return fov_y_deg_; }
  float scene_diagonal() const { return scene_diagonal_; }
  glm::mat4 view() const;
  // `aspect`: width / height. Near and far planes span the scene around the
  // camera.
  glm::mat4 projection(float aspect) const;
  // Where `world` lands on a `width` x `height` image (pixels, y down).
  glm::vec2 project(const glm::vec3& world, int width, int height) const;
  // The world length one pixel of a `height`-pixel image spans at `point`'s
  // depth, and the camera's right and up axes there.
  float pixel_size_at(const glm::vec3& point, int height) const;
  glm::vec3 right_axis() const;
  glm::vec3 up_axis() const;

  // Mouse drags, in pixels.
  void orbit(float dx, float dy);
  void dolly(float factor);  // distance times factor, within the bounds

 private:
  glm::vec3 target_{0.0f}, up_{0.0f, 1.0f, 0.0f};
  glm::vec3 base_forward_{0.0f, 0.0f, -1.0f};  // scene camera's direction at yaw = pitch = 0
  float distance_ = 1.0f, yaw_ = 0.0f, pitch_ = 0.0f, fov_y_deg_ = 45.0f;
  float scene_diagonal_ = 1.0f;
};

}  // namespace bounce::views
