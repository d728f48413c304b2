// The preview's light probes: the overlay of probe spheres and the
// probe-lit sphere that stands for a moving object (preview_widget.h).
#include <algorithm>
#include <limits>
#include <mutex>
#include <vector>

#include <QOpenGLShaderProgram>
#include <glm/gtc/type_ptr.hpp>

#include "bounce/scene.h"
#include "preview_lighting.h"
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
  spheres_dirty_ = true;
  update();
}

void PreviewWidget::set_sphere_shown(bool on) {
  sphere_shown_ = on;
  spheres_dirty_ = true;
  update();
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
  spheres_dirty_ = true;
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

// Into the G-buffer after the scene, so the composite lights the spheres
// with the same direct light, occlusion and exposure.
void PreviewWidget::draw_spheres(const glm::mat4& view, const glm::mat4& projection) {
  const bool probes = probes_shown_ && has_probes();
  const bool sphere = sphere_shown_ && has_probes();
  if (!probes && !sphere) return;
  if (spheres_dirty_) {
    std::vector<SphereInstance> spheres;
    if (sphere)
      spheres.push_back({sphere_position_, sphere_radius(), kSphereAlbedo, false, sphere_sh_});
    const std::vector<glm::vec3>& at = lighting_->probe_positions();
    if (probes && probe_sh_.size() == at.size() * kShCoefficients)
      for (std::size_t p = 0; p < at.size(); ++p) {
        SphereInstance s{at[p], kProbeRadiusCells * lighting_->cell_size(), glm::vec3(0.0f), true};
        std::copy_n(probe_sh_.begin() + static_cast<std::ptrdiff_t>(p * kShCoefficients),
                    kShCoefficients, s.sh.begin());
        spheres.push_back(s);
      }
    spheres_.set(spheres);
    spheres_dirty_ = false;
  }
  programs_.sphere->bind();
  glUniformMatrix4fv(programs_.sphere->uniformLocation("view"), 1, GL_FALSE, glm::value_ptr(view));
  glUniformMatrix4fv(programs_.sphere->uniformLocation("projection"), 1, GL_FALSE,
                     glm::value_ptr(projection));
  spheres_.draw(*programs_.sphere);
}

}  // namespace bounce::views
