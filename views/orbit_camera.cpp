#include "orbit_camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace bounce::views {

void OrbitCamera::reset(const Camera& camera, float diagonal) {
  scene_diagonal_ = std::max(1e-6f, diagonal);
  target_ = camera.target;
  up_ = glm::normalize(camera.up);
  const glm::vec3 to_target = camera.target - camera.position;
  distance_ = std::max(1e-3f * scene_diagonal_, glm::length(to_target));
  base_forward_ =
      glm::length(to_target) > 0.0f ? to_target / glm::length(to_target) : glm::vec3(0, 0, -1);
  yaw_ = pitch_ = 0.0f;
  fov_y_deg_ = camera.fov_y_deg;
}

glm::vec3 OrbitCamera::eye() const {
  // Turn the scene camera's direction by yaw about up, then by pitch about
  // the camera's right axis.
  const glm::mat4 yaw = glm::rotate(glm::mat4(1.0f), yaw_, up_);
  glm::vec3 forward = glm::vec3(yaw * glm::vec4(base_forward_, 0.0f));
  const glm::vec3 right = glm::normalize(glm::cross(forward, up_));
  forward = glm::vec3(glm::rotate(glm::mat4(1.0f), pitch_, right) * glm::vec4(forward, 0.0f));
  return target_ - distance_ * forward;
}

glm::mat4 OrbitCamera::view() const { return glm::lookAt(eye(), target_, up_); }

glm::mat4 OrbitCamera::projection(float aspect) const {
  const float far_plane = distance_ + 2.0f * scene_diagonal_;
  return glm::perspective(glm::radians(fov_y_deg_), aspect, 1e-3f * far_plane, far_plane);
}

glm::vec2 OrbitCamera::project(const glm::vec3& world, int width, int height) const {
  const float aspect =
      static_cast<float>(std::max(1, width)) / static_cast<float>(std::max(1, height));
  const glm::vec4 clip = projection(aspect) * view() * glm::vec4(world, 1.0f);
  const glm::vec3 ndc = glm::vec3(clip) / clip.w;
  return {(0.5f * ndc.x + 0.5f) * static_cast<float>(width),
          (0.5f - 0.5f * ndc.y) * static_cast<float>(height)};
}

glm::vec3 OrbitCamera::right_axis() const {
  return glm::normalize(glm::cross(glm::normalize(target_ - eye()), up_));
}

glm::vec3 OrbitCamera::up_axis() const {
  return glm::cross(right_axis(), glm::normalize(target_ - eye()));
}

float OrbitCamera::pixel_size_at(const glm::vec3& point, int height) const {
  const glm::vec3 e = eye();
  const float depth = std::max(1e-3f, glm::dot(point - e, glm::normalize(target_ - e)));
  return 2.0f * depth * std::tan(0.5f * glm::radians(fov_y_deg_)) /
         static_cast<float>(std::max(1, height));
}

void OrbitCamera::orbit(float dx, float dy) {
  yaw_ -= 0.01f * dx;
  pitch_ = std::clamp(pitch_ - 0.01f * dy, -1.5f, 1.5f);
}

void OrbitCamera::dolly(float factor) {
  distance_ = std::clamp(distance_ * factor, 0.01f * scene_diagonal_, 20.0f * scene_diagonal_);
}

}  // namespace bounce::views
