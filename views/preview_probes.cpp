// The preview's light probes: the overlay of probe spheres and the
// probe-lit object (a sphere or a loaded mesh) that stands for a moving
// thing (preview_widget.h).
#include <algorithm>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <QOpenGLShaderProgram>
#include <glm/gtc/type_ptr.hpp>

#include "bounce/scene.h"
#include "preview_lighting.h"
#include "preview_object_mesh.h"
#include "preview_widget.h"

namespace bounce::views {

namespace {

// A probe's sphere in the overlay: small beside the voxel that separates
// probes, so that neighbours stay apart.
constexpr float kProbeRadiusCells = 0.12f;
// The moving sphere: about an object's size at the bake's grain, never so
// small that it vanishes in a large scene.
constexpr float kSphereRadiusCells = 0.35f;
constexpr float kSphereRadiusDiagonal = 0.02f;
// A light grey, as a material people judge colour bleeding on.
constexpr glm::vec3 kSphereAlbedo{0.8f};

}  // namespace

bool PreviewWidget::has_probes() const { return lighting_ && lighting_->has_probes(); }

std::size_t PreviewWidget::probe_count() const {
  return lighting_ ? lighting_->probe_positions().size() : 0;
}

void PreviewWidget::set_probes_shown(bool on) {
  probes_shown_ = on;
  if (on) refresh_probes();
  shapes_dirty_ = true;
  update();
}

void PreviewWidget::set_sphere_shown(bool on) {
  sphere_shown_ = on;
  if (on) refresh_probes();
  shapes_dirty_ = true;
  update();
}

std::optional<glm::vec3> PreviewWidget::probes_wanted() const {
  if ((probes_shown_ || sphere_shown_) && has_probes()) return sphere_position_;
  return std::nullopt;
}

void PreviewWidget::refresh_probes() {
  if (!has_probes() || probes_current_) return;
  PreviewLighting::Solve s;
  {
    std::lock_guard<std::mutex> lock(*lighting_mutex_);
    lighting_->solve_probes(sphere_position_, s);
  }
  probe_sh_ = std::move(s.probe_sh);
  sphere_sh_ = s.sphere_sh;
  probe_seconds_ = s.probe_seconds;
  probes_current_ = true;
  shapes_dirty_ = true;
}

float PreviewWidget::sphere_radius() const {
  if (!lighting_) return 0.0f;
  return std::max(kSphereRadiusCells * lighting_->cell_size(),
                  kSphereRadiusDiagonal * camera_.scene_diagonal());
}

void PreviewWidget::set_sphere_position(const glm::vec3& position) {
  sphere_position_ = position;
  if (has_probes()) {
    std::lock_guard<std::mutex> lock(*lighting_mutex_);
    sphere_sh_ = lighting_->sh_at(position);
  }
  shapes_dirty_ = true;
  update();
}

void PreviewWidget::place_sphere() {
  const Bounds b = lighting_->scene().bounds();
  const glm::vec3 centre = 0.5f * (b.lo + b.hi);
  sphere_position_ = centre;
  float best = std::numeric_limits<float>::max();
  for (const glm::vec3& p : lighting_->probe_positions()) {
    const glm::vec3 d = p - centre;
    if (glm::dot(d, d) < best) {
      best = glm::dot(d, d);
      sphere_position_ = p;
    }
  }
}

void PreviewWidget::load_object(const std::string& path) {
  ObjectMesh mesh = load_object_mesh(path);
  object_name_ = mesh.name;
  object_.set_mesh(std::move(mesh.corners), std::move(mesh.normals));
  shapes_dirty_ = true;
  update();
}

void PreviewWidget::use_sphere() {
  object_name_ = "sphere";
  object_.set_mesh({}, {});
  shapes_dirty_ = true;
  update();
}

void PreviewWidget::upload_shapes() {
  const bool probes = probes_shown_ && has_probes();
  std::vector<ShapeInstance> object, spheres;
  if (sphere_shown_ && has_probes())
    object.push_back({sphere_position_, sphere_radius(), kSphereAlbedo, false, sphere_sh_});
  const std::vector<glm::vec3>& at = lighting_->probe_positions();
  if (probes && probe_sh_.size() == at.size() * kShCoefficients)
    for (std::size_t p = 0; p < at.size(); ++p) {
      ShapeInstance s{at[p], kProbeRadiusCells * lighting_->cell_size(), glm::vec3(0.0f), true};
      std::copy_n(probe_sh_.begin() + static_cast<std::ptrdiff_t>(p * kShCoefficients),
                  kShCoefficients, s.sh.begin());
      spheres.push_back(s);
    }
  object_.set(object);
  probe_spheres_.set(spheres);
  shapes_dirty_ = false;
}

// Into the G-buffer after the scene, so the composite lights the shapes
// with the same direct light and exposure.
void PreviewWidget::draw_shapes(const glm::mat4& view, const glm::mat4& projection) {
  if (!(probes_shown_ || sphere_shown_) || !has_probes()) return;
  if (shapes_dirty_) upload_shapes();
  programs_.shape->bind();
  glUniformMatrix4fv(programs_.shape->uniformLocation("view"), 1, GL_FALSE, glm::value_ptr(view));
  glUniformMatrix4fv(programs_.shape->uniformLocation("projection"), 1, GL_FALSE,
                     glm::value_ptr(projection));
  object_.draw(*programs_.shape);
  probe_spheres_.draw(*programs_.shape);
}

}  // namespace bounce::views
