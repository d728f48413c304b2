#include "preview_widget.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>

#include <QMouseEvent>
#include <QOpenGLShaderProgram>
#include <QPainter>
#include <QSurfaceFormat>
#include <QTimer>
#include <QVector2D>
#include <QVector3D>
#include <QWheelEvent>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "bounce/error.h"
#include "bounce/export.h"
#include "bounce/pictures.h"
#include "bounce/scene.h"
#include "preview_corners.h"
#include "preview_lighting.h"
#include "preview_programs.h"
#include "preview_tangents.h"
#include "view_jobs.h"

namespace bounce::views {

struct PreviewWidget::SolveResult {
  PreviewLighting::Solve solve;
};

PreviewWidget::PreviewWidget(ViewJobs& jobs, QWidget* parent) : QOpenGLWidget(parent), jobs_(jobs) {
  QSurfaceFormat format = QSurfaceFormat::defaultFormat();
  format.setVersion(3, 3);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setDepthBufferSize(24);
  setFormat(format);
  setFocusPolicy(Qt::StrongFocus);
  setMinimumSize(64, 64);

  // Paper 002: S_t = (2 rnd - 1, 2 rnd - 1, rnd) in the tangent frame; the
  // points outside the unit half ball are drawn again, so the samples fill
  // the hemisphere of radius R around P as the paper asks. Fixed seed: the
  // same picture every run.
  std::mt19937 random(20021u);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  while (ao_kernel_.size() < static_cast<std::size_t>(kAoSamples)) {
    const glm::vec3 s(2.0f * unit(random) - 1.0f, 2.0f * unit(random) - 1.0f, unit(random));
    if (glm::dot(s, s) <= 1.0f) ao_kernel_.push_back(s);
  }
  clock_.start();
}

PreviewWidget::~PreviewWidget() {
  if (gl_ready_) {
    makeCurrent();
    release_gl();
    doneCurrent();
  }
}

std::size_t PreviewWidget::vertex_count() const {
  return lighting_ ? lighting_->mesh().positions.size() : 0;
}

std::size_t PreviewWidget::triangle_count() const {
  return lighting_ ? lighting_->mesh().triangles.size() : 0;
}

void PreviewWidget::clear() {
  jobs_.forget(this);
  lighting_.reset();
  data_.reset();
  vertex_indirect_.clear();
  probe_sh_.clear();
  sphere_sh_ = {};
  shapes_dirty_ = true;
  exposure_full_.reset();
  exposure_indirect_.reset();
  mesh_dirty_ = true;
  update();
}

void PreviewWidget::set_data(std::shared_ptr<const BakeViewData> bake) {
  clear();
  auto lighting = std::make_shared<PreviewLighting>(bake);
  data_ = std::move(bake);
  lighting_ = std::move(lighting);
  reset_camera();
  light_position_ = lighting_->light().position;
  // Solve twice to measure: the policy (UI thread or worker) follows from
  // what a light move costs here. The faster of the two counts: the first
  // also pays one-time costs (OpenMP's threads, cold caches). The first is
  // a little off the light's place, so that the second is a move, as a drag
  // pays it (a solve where the light already is traces no shadow rays);
  // then the light is settled there.
  const glm::vec3 nudge(1e-3f * glm::length(lighting_->scene().bounds().extent()));
  place_sphere();
  // Timed with the probes, as a move costs when they are shown.
  const std::optional<glm::vec3> probes =
      has_probes() ? std::optional(sphere_position_) : std::nullopt;
  PreviewLighting::Solve s = lighting_->solve(light_position_ + nudge, false, probes);
  const double first = s.frame_seconds + s.transfer_seconds + s.probe_seconds;
  s = lighting_->solve(light_position_, false, probes);
  solve_on_worker_ =
      std::min(first, s.frame_seconds + s.transfer_seconds + s.probe_seconds) > kUiSolveBudget;
  if (!s.settled) s = lighting_->solve(light_position_, true, probes);
  apply({std::move(s)});
  mesh_dirty_ = true;
  update();
}

void PreviewWidget::export_lit_glb(const std::string& path) {
  if (!lighting_) throw Error(path, "nothing to export: open or bake a scene first");
  LitMesh mesh;
  {
    std::lock_guard<std::mutex> lock(*lighting_mutex_);
    mesh = lighting_->lit_mesh(light_position_);
  }
  // The scene is never changed after construction: no lock needed to read it.
  write_lit_scene_glb(path, lighting_->scene(), mesh, std::filesystem::path(path).stem().string());
}

void PreviewWidget::set_passes(Passes passes) {
  passes_ = passes;
  update();
}

void PreviewWidget::set_overlay(bool on) {
  overlay_ = on;
  update();
}

void PreviewWidget::set_light_position(const glm::vec3& position, bool wait) {
  if (!lighting_) return;
  light_position_ = position;
  shadow_dirty_ = true;  // the direct light follows at once, the indirect when solved
  solve_at(position, wait);
}

void PreviewWidget::solve_at(const glm::vec3& position, bool wait) {
  if (wait || !solve_on_worker_) {
    std::lock_guard<std::mutex> lock(*lighting_mutex_);
    apply({lighting_->solve(position, wait, probes_wanted())});
  } else {
    jobs_.run<SolveResult>(
        this, kSolveJob,
        [lighting = lighting_, mutex = lighting_mutex_, position,
         probes = probes_wanted()](const ViewJobs::KeepGoing&) {
          std::lock_guard<std::mutex> lock(*mutex);
          return SolveResult{lighting->solve(position, false, probes)};
        },
        [this](SolveResult r) { apply(std::move(r)); },
        [this](const QString& message) {
          gl_error_ = tr("solve failed: ") + message;
          update();
        });
  }
  update();
}

void PreviewWidget::apply(SolveResult result) {
  PreviewLighting::Solve& s = result.solve;
  solved_light_ = s.light_position;
  solved_settled_ = s.settled;
  vertex_indirect_ = std::move(s.vertex_irradiance);
  frame_seconds_ = s.frame_seconds;
  transfer_seconds_ = s.transfer_seconds;
  probe_seconds_ = s.probe_seconds;
  indirect_dirty_ = true;
  probes_current_ = s.probes_solved;
  if (s.probes_solved) {
    probe_sh_ = std::move(s.probe_sh);
    sphere_sh_ = s.sphere_sh;
    shapes_dirty_ = true;
    // The sphere moved while this light was solved: blend it where it is now.
    if (s.sphere_position != sphere_position_) set_sphere_position(sphere_position_);
  } else if (probes_wanted()) {
    refresh_probes();  // switched on while this light was solved without them
  }
  update();
  emit solved();
  // Where the light stopped, solve again until its shadows are exact; from
  // the event loop, so that each frame reaches the screen and a new move
  // takes over.
  if (!solved_settled_ && solved_light_ == light_position_)
    QTimer::singleShot(0, this, [this] {
      if (lighting_ && !solved_settled_ && solved_light_ == light_position_)
        solve_at(light_position_, false);
    });
}

// --- camera ------------------------------------------------------------------

void PreviewWidget::reset_camera() {
  const Scene& scene = lighting_->scene();
  camera_.reset(scene.camera, glm::length(scene.bounds().extent()));
}

float PreviewWidget::aspect() const {
  return static_cast<float>(std::max(1, width())) / static_cast<float>(std::max(1, height()));
}

QPointF PreviewWidget::project(const glm::vec3& world) const {
  const glm::vec2 p = camera_.project(world, width(), height());
  return {p.x, p.y};
}

glm::vec3 PreviewWidget::inside_scene(const glm::vec3& p) const {
  const Bounds b = lighting_->scene().bounds();
  // Inside the scene, a little off its outer surfaces.
  const glm::vec3 margin = 0.01f * b.extent();
  return glm::clamp(p, b.lo + margin, b.hi - margin);
}

void PreviewWidget::move_light_by(const glm::vec3& delta) {
  if (!lighting_) return;
  set_light_position(inside_scene(light_position_ + delta));
}

void PreviewWidget::mousePressEvent(QMouseEvent* event) { last_mouse_ = event->pos(); }

void PreviewWidget::mouseMoveEvent(QMouseEvent* event) {
  const QPoint d = event->pos() - last_mouse_;
  last_mouse_ = event->pos();
  if (!lighting_) return;
  if ((event->buttons() & Qt::LeftButton) && (event->modifiers() & Qt::ShiftModifier) &&
      sphere_shown_) {
    const float per_pixel = camera_.pixel_size_at(sphere_position_, height());
    set_sphere_position(inside_scene(sphere_position_ +
                                     per_pixel * (static_cast<float>(d.x()) * camera_.right_axis() -
                                                  static_cast<float>(d.y()) * camera_.up_axis())));
  } else if ((event->buttons() & Qt::LeftButton) && (event->modifiers() & Qt::ControlModifier)) {
    // Move the light with the mouse: one pixel is what a pixel spans at the
    // light's distance from the eye.
    const float per_pixel = camera_.pixel_size_at(light_position_, height());
    move_light_by(per_pixel * (static_cast<float>(d.x()) * camera_.right_axis() -
                               static_cast<float>(d.y()) * camera_.up_axis()));
  } else if (event->buttons() & Qt::LeftButton) {
    camera_.orbit(static_cast<float>(d.x()), static_cast<float>(d.y()));
    update();
  } else if (event->buttons() & Qt::RightButton) {
    camera_.dolly(std::exp(0.01f * static_cast<float>(d.y())));
    update();
  }
}

void PreviewWidget::wheelEvent(QWheelEvent* event) {
  if (!lighting_) return;
  const float steps = static_cast<float>(event->angleDelta().y()) / 120.0f;
  if (event->modifiers() & Qt::ControlModifier) {
    const glm::vec3 forward = glm::normalize(camera_.target() - camera_.eye());
    move_light_by(0.02f * camera_.scene_diagonal() * steps * forward);
  } else {
    camera_.dolly(std::pow(0.9f, steps));
    update();
  }
}

}  // namespace bounce::views
