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
  glm::vec3 light_position{0.0f};
  std::vector<glm::vec3> vertex_indirect;
  double frame_seconds = 0.0, transfer_seconds = 0.0;
  bool settled = true;
};

namespace {

// The six faces of a cube map as OpenGL orders them, with the up vectors
// its face layout implies.
constexpr glm::vec3 kCubeForward[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                       {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
constexpr glm::vec3 kCubeUp[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1},
                                  {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};

}  // namespace

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
  PreviewLighting::Solve s = lighting_->solve(light_position_ + nudge);
  const double first = s.frame_seconds + s.transfer_seconds;
  s = lighting_->solve(light_position_);
  solve_on_worker_ = std::min(first, s.frame_seconds + s.transfer_seconds) > kUiSolveBudget;
  if (!s.settled) s = lighting_->solve(light_position_, true);
  apply({s.light_position, s.vertex_irradiance, s.frame_seconds, s.transfer_seconds, s.settled});
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
    const PreviewLighting::Solve s = lighting_->solve(position, wait);
    apply({s.light_position, s.vertex_irradiance, s.frame_seconds, s.transfer_seconds, s.settled});
  } else {
    jobs_.run<SolveResult>(
        this, kSolveJob,
        [lighting = lighting_, mutex = lighting_mutex_, position](const ViewJobs::KeepGoing&) {
          std::lock_guard<std::mutex> lock(*mutex);
          const PreviewLighting::Solve s = lighting->solve(position);
          return SolveResult{s.light_position, s.vertex_irradiance, s.frame_seconds,
                             s.transfer_seconds, s.settled};
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
  solved_light_ = result.light_position;
  solved_settled_ = result.settled;
  vertex_indirect_ = std::move(result.vertex_indirect);
  frame_seconds_ = result.frame_seconds;
  transfer_seconds_ = result.transfer_seconds;
  indirect_dirty_ = true;
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

void PreviewWidget::move_light_by(const glm::vec3& delta) {
  if (!lighting_) return;
  const Bounds b = lighting_->scene().bounds();
  // Stay inside the scene, a little off its outer surfaces.
  const glm::vec3 margin = 0.01f * b.extent();
  set_light_position(glm::clamp(light_position_ + delta, b.lo + margin, b.hi - margin));
}

void PreviewWidget::mousePressEvent(QMouseEvent* event) { last_mouse_ = event->pos(); }

void PreviewWidget::mouseMoveEvent(QMouseEvent* event) {
  const QPoint d = event->pos() - last_mouse_;
  last_mouse_ = event->pos();
  if (!lighting_) return;
  if ((event->buttons() & Qt::LeftButton) && (event->modifiers() & Qt::ControlModifier)) {
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

// --- OpenGL ------------------------------------------------------------------

void PreviewWidget::initializeGL() {
  if (!initializeOpenGLFunctions()) {
    gl_error_ = tr("OpenGL 3.3 core profile is not available");
    return;
  }
  try {
    programs_ = PreviewPrograms::build();
  } catch (const std::exception& e) {
    gl_error_ = QString::fromStdString(e.what());
    return;
  }
  glGenVertexArrays(1, &empty_vao_);

  // Shadow cube: depth only, distance / far per texel (preview_shadow.frag).
  glGenTextures(1, &shadow_cube_);
  glBindTexture(GL_TEXTURE_CUBE_MAP, shadow_cube_);
  for (int f = 0; f < 6; ++f)
    glTexImage2D(static_cast<GLenum>(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f), 0, GL_DEPTH_COMPONENT24,
                 kShadowSize, kShadowSize, 0, GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  glGenFramebuffers(1, &shadow_fbo_);

  // V_r per pixel (the SSAO rotation, docs/studio.md): (2 rnd - 1, 2 rnd - 1, 0),
  // tiled 4 x 4.
  std::mt19937 random(20022u);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<float> noise;
  for (int k = 0; k < 16; ++k) {
    noise.push_back(2.0f * unit(random) - 1.0f);
    noise.push_back(2.0f * unit(random) - 1.0f);
    noise.push_back(0.0f);
  }
  glGenTextures(1, &noise_texture_);
  glBindTexture(GL_TEXTURE_2D, noise_texture_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, 4, 4, 0, GL_RGB, GL_FLOAT, noise.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);

  gl_ready_ = true;
  mesh_dirty_ = true;
  shadow_dirty_ = true;
}

void PreviewWidget::release_gl() {
  targets_.release();
  if (mesh_vao_) glDeleteVertexArrays(1, &mesh_vao_);
  if (empty_vao_) glDeleteVertexArrays(1, &empty_vao_);
  if (static_vbo_) glDeleteBuffers(1, &static_vbo_);
  if (indirect_vbo_) glDeleteBuffers(1, &indirect_vbo_);
  material_images_.release();
  draws_.clear();
  if (shadow_fbo_) glDeleteFramebuffers(1, &shadow_fbo_);
  if (shadow_cube_) glDeleteTextures(1, &shadow_cube_);
  if (noise_texture_) glDeleteTextures(1, &noise_texture_);
  mesh_vao_ = empty_vao_ = static_vbo_ = indirect_vbo_ = shadow_fbo_ = shadow_cube_ =
      noise_texture_ = 0;
  programs_ = {};
  gl_ready_ = false;
}

void PreviewWidget::resizeGL(int, int) {}

void PreviewWidget::upload_mesh() {
  mesh_dirty_ = false;
  if (mesh_vao_) glDeleteVertexArrays(1, &mesh_vao_);
  if (static_vbo_) glDeleteBuffers(1, &static_vbo_);
  if (indirect_vbo_) glDeleteBuffers(1, &indirect_vbo_);
  material_images_.release();
  mesh_vao_ = static_vbo_ = indirect_vbo_ = 0;
  draws_.clear();
  corner_count_ = 0;
  corner_vertex_.clear();
  if (!lighting_) return;
  const Scene& scene = lighting_->scene();
  PreviewCorners corners = preview_corners(scene, lighting_->mesh());
  for (const PreviewCorners::MaterialRange& range : corners.materials) {
    MaterialDraw draw;
    draw.first = static_cast<GLint>(range.first);
    draw.count = static_cast<GLsizei>(range.count);
    draw.material = range.material;
    draws_.push_back(draw);
  }
  corner_vertex_ = std::move(corners.vertex);
  for (MaterialDraw& draw : draws_) draw.images = material_images_.upload(scene, draw.material);
  corner_count_ = static_cast<GLsizei>(corner_vertex_.size());
  glGenVertexArrays(1, &mesh_vao_);
  glBindVertexArray(mesh_vao_);
  glGenBuffers(1, &static_vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, static_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(corners.floats.size() * sizeof(float)),
               corners.floats.data(), GL_STATIC_DRAW);
  const GLsizei stride = PreviewCorners::kFloats * sizeof(float);
  for (GLuint k = 0; k < 4; ++k) {
    glEnableVertexAttribArray(k);
    glVertexAttribPointer(
        k, 3, GL_FLOAT, GL_FALSE, stride,
        reinterpret_cast<const void*>(static_cast<std::uintptr_t>(k * 3 * sizeof(float))));
  }
  glEnableVertexAttribArray(5);
  glVertexAttribPointer(
      5, 2, GL_FLOAT, GL_FALSE, stride,
      reinterpret_cast<const void*>(static_cast<std::uintptr_t>(12 * sizeof(float))));
  glEnableVertexAttribArray(6);
  glVertexAttribPointer(
      6, 1, GL_FLOAT, GL_FALSE, stride,
      reinterpret_cast<const void*>(static_cast<std::uintptr_t>(14 * sizeof(float))));
  glEnableVertexAttribArray(7);
  glVertexAttribPointer(
      7, 4, GL_FLOAT, GL_FALSE, stride,
      reinterpret_cast<const void*>(static_cast<std::uintptr_t>(15 * sizeof(float))));
  glGenBuffers(1, &indirect_vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, indirect_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(corner_vertex_.size() * sizeof(glm::vec3)),
               nullptr, GL_DYNAMIC_DRAW);
  glEnableVertexAttribArray(4);
  glVertexAttribPointer(4, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindVertexArray(0);
  indirect_dirty_ = true;
}

void PreviewWidget::draw_mesh(QOpenGLShaderProgram& program) {
  const Scene& scene = lighting_->scene();
  program.setUniformValue("albedo_texture", 0);
  program.setUniformValue("alpha_mask", 1);
  program.setUniformValue("normal_map", 2);
  program.setUniformValue("emission_texture", 3);
  glBindVertexArray(mesh_vao_);
  for (const MaterialDraw& draw : draws_) {
    const Material& m = scene.materials[draw.material];
    const PreviewMaterialImages::Images& own = draw.images;
    const GLuint normal_map = passes_.normal_maps ? own.normal_map : 0;
    const GLuint images[] = {own.texture, own.mask, normal_map, own.emission};
    for (int unit = 0; unit < 4; ++unit) {
      glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
      glBindTexture(GL_TEXTURE_2D, images[unit]);
    }
    program.setUniformValue("has_texture", own.texture != 0);
    program.setUniformValue("has_normal_map", normal_map != 0);
    program.setUniformValue("normal_scale", m.normal_scale);
    program.setUniformValue("has_emission_texture", own.emission != 0);
    program.setUniformValue("has_mask", own.mask != 0);
    program.setUniformValue("constant_mask",
                            m.alpha_mask != nullptr && m.alpha_mask->is_constant());
    program.setUniformValue("alpha_factor", m.alpha_factor);
    program.setUniformValue("alpha_cutoff", m.alpha_cutoff);
    glDrawArrays(GL_TRIANGLES, draw.first, draw.count);
  }
  glActiveTexture(GL_TEXTURE0);
  glBindVertexArray(0);
}

void PreviewWidget::upload_indirect() {
  indirect_dirty_ = false;
  if (!indirect_vbo_ || vertex_indirect_.empty()) return;
  std::vector<glm::vec3> corners(corner_vertex_.size());
  for (std::size_t k = 0; k < corners.size(); ++k) corners[k] = vertex_indirect_[corner_vertex_[k]];
  glBindBuffer(GL_ARRAY_BUFFER, indirect_vbo_);
  glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(corners.size() * sizeof(glm::vec3)),
                  corners.data());
}

void PreviewWidget::render_shadow_map() {
  shadow_dirty_ = false;
  const float far_plane = 2.0f * camera_.scene_diagonal();
  const glm::mat4 projection =
      glm::perspective(glm::radians(90.0f), 1.0f, 1e-3f * far_plane, far_plane);
  glBindFramebuffer(GL_FRAMEBUFFER, shadow_fbo_);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  glViewport(0, 0, kShadowSize, kShadowSize);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);  // single-sided walls shadow from both sides
  programs_.shadow->bind();
  programs_.shadow->setUniformValue("far_plane", far_plane);
  glUniform3fv(programs_.shadow->uniformLocation("light_position"), 1,
               glm::value_ptr(light_position_));
  for (int f = 0; f < 6; ++f) {
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT,
                           static_cast<GLenum>(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f), shadow_cube_,
                           0);
    glClear(GL_DEPTH_BUFFER_BIT);
    const glm::mat4 view =
        glm::lookAt(light_position_, light_position_ + kCubeForward[f], kCubeUp[f]);
    const glm::mat4 vp = projection * view;
    glUniformMatrix4fv(programs_.shadow->uniformLocation("light_view_projection"), 1, GL_FALSE,
                       glm::value_ptr(vp));
    draw_mesh(*programs_.shadow);  // alpha-tested: light passes where masks cut away
  }
}

void PreviewWidget::render(GLuint target) {
  const qreal ratio = devicePixelRatioF();
  const int w = std::max(1, static_cast<int>(width() * ratio));
  const int h = std::max(1, static_cast<int>(height() * ratio));
  if (!gl_ready_ || !lighting_) {
    glBindFramebuffer(GL_FRAMEBUFFER, target);
    glViewport(0, 0, w, h);
    glClearColor(0.12f, 0.12f, 0.13f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    return;
  }
  if (mesh_dirty_) upload_mesh();
  if (indirect_dirty_) upload_indirect();
  targets_.ensure_size(w, h);
  if (shadow_dirty_) render_shadow_map();

  const glm::mat4 view = camera_.view();
  const glm::mat4 projection = camera_.projection(aspect());

  // 1. G-buffer.
  glBindFramebuffer(GL_FRAMEBUFFER, targets_.gbuffer_fbo());
  glViewport(0, 0, w, h);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);  // from outside, the walls' backs open the box up
  glCullFace(GL_BACK);
  const float far_position[4] = {0.0f, 0.0f, -1e4f, 0.0f};
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  glClearBufferfv(GL_COLOR, 0, far_position);
  for (int k = 1; k < PreviewTargets::kGbufferTargets; ++k) glClearBufferfv(GL_COLOR, k, zero);
  glClear(GL_DEPTH_BUFFER_BIT);
  programs_.gbuffer->bind();
  glUniformMatrix4fv(programs_.gbuffer->uniformLocation("view"), 1, GL_FALSE, glm::value_ptr(view));
  glUniformMatrix4fv(programs_.gbuffer->uniformLocation("projection"), 1, GL_FALSE,
                     glm::value_ptr(projection));
  draw_mesh(*programs_.gbuffer);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DEPTH_TEST);

  auto bind = [this](int unit, GLenum kind, GLuint texture) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
    glBindTexture(kind, texture);
  };
  glBindVertexArray(empty_vao_);

  // 2-3. Occlusion and its blur (only when they are shown).
  const bool ao = passes_.ao && passes_.indirect;
  if (ao) {
    glBindFramebuffer(GL_FRAMEBUFFER, targets_.ao_fbo());
    programs_.ssao->bind();
    bind(0, GL_TEXTURE_2D, targets_.gbuffer_texture(0));
    bind(1, GL_TEXTURE_2D, targets_.gbuffer_texture(1));
    bind(2, GL_TEXTURE_2D, targets_.gbuffer_texture(2));
    bind(3, GL_TEXTURE_2D, noise_texture_);
    programs_.ssao->setUniformValue("g_position", 0);
    programs_.ssao->setUniformValue("g_normal", 1);
    programs_.ssao->setUniformValue("g_albedo", 2);
    programs_.ssao->setUniformValue("noise", 3);
    glUniform3fv(programs_.ssao->uniformLocation("kernel"), kAoSamples,
                 glm::value_ptr(ao_kernel_.front()));
    programs_.ssao->setUniformValue("kernel_size", kAoSamples);
    // R and delta belong to the scene (the paper picks them per scene): a
    // twentieth of its diagonal reaches into corners without darkening whole
    // walls; delta is above the RGBA16F position's step at this depth.
    programs_.ssao->setUniformValue("radius", 0.05f * camera_.scene_diagonal());
    programs_.ssao->setUniformValue("delta", 0.005f * camera_.scene_diagonal());
    glUniformMatrix4fv(programs_.ssao->uniformLocation("projection"), 1, GL_FALSE,
                       glm::value_ptr(projection));
    programs_.ssao->setUniformValue(
        "noise_scale", QVector2D(static_cast<float>(w) / 4.0f, static_cast<float>(h) / 4.0f));
    glDrawArrays(GL_TRIANGLES, 0, 3);

    glBindFramebuffer(GL_FRAMEBUFFER, targets_.blur_fbo());
    programs_.blur->bind();
    bind(0, GL_TEXTURE_2D, targets_.ao_texture());
    programs_.blur->setUniformValue("ao", 0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }

  // 4. Lighting and composite. The exposure is fixed once, from the first
  // frame after set_data (the light where the scene puts it): the core's
  // ToneMap rule (99th percentile of luminance to 0.9, as `bounce solve`'s
  // camera pictures) on that frame's linear pixels, with and without the
  // direct light. Fixed, so a moving light brightens and darkens the picture.
  if (!exposure_full_) calibrate_exposure(w, h);
  glBindFramebuffer(GL_FRAMEBUFFER, target);
  glViewport(0, 0, w, h);
  // Indirect alone is several times dimmer than the whole: it has its own
  // exposure, so its colours stay readable.
  const bool indirect_only = passes_.indirect && !passes_.direct;
  draw_composite(passes_.direct, passes_.indirect, ao,
                 indirect_only ? *exposure_indirect_ : *exposure_full_, false);
  glBindVertexArray(0);
  glActiveTexture(GL_TEXTURE0);
}

void PreviewWidget::calibrate_exposure(int width, int height) {
  GLuint fbo = 0, texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
  glViewport(0, 0, width, height);
  std::vector<float> pixels(static_cast<std::size_t>(width) * height * 4);
  auto exposure = [&](bool direct) {
    draw_composite(direct, true, false, 1.0f, true);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, pixels.data());
    std::vector<float> lum;
    lum.reserve(pixels.size() / 4);
    for (std::size_t k = 0; k < pixels.size(); k += 4)
      lum.push_back(luminance({pixels[k], pixels[k + 1], pixels[k + 2]}));
    return ToneMap::exposure_for(std::move(lum));
  };
  exposure_full_ = exposure(true);
  exposure_indirect_ = exposure(false);
  glDeleteFramebuffers(1, &fbo);
  glDeleteTextures(1, &texture);
}

void PreviewWidget::draw_composite(bool direct, bool indirect, bool ao, float exposure,
                                   bool linear) {
  auto bind = [this](int unit, GLenum kind, GLuint t) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
    glBindTexture(kind, t);
  };
  const glm::mat4 view = camera_.view();
  programs_.composite->bind();
  for (int k = 0; k < PreviewTargets::kGbufferTargets; ++k)
    bind(k, GL_TEXTURE_2D, targets_.gbuffer_texture(k));
  bind(5, GL_TEXTURE_2D, targets_.blur_texture());
  bind(6, GL_TEXTURE_CUBE_MAP, shadow_cube_);
  const char* samplers[] = {"g_position", "g_normal", "g_albedo",  "g_emission",
                            "g_indirect", "ao",       "shadow_map"};
  for (int k = 0; k < 7; ++k) programs_.composite->setUniformValue(samplers[k], k);
  const Light& light = lighting_->light();
  const glm::mat3 view_rotation(view);
  const glm::vec3 light_view = glm::vec3(view * glm::vec4(light_position_, 1.0f));
  const glm::vec3 power = light.color * light.intensity;
  const glm::vec3 axis = view_rotation * glm::normalize(light.direction);
  const glm::mat3 to_world = glm::transpose(view_rotation);
  glUniformMatrix3fv(programs_.composite->uniformLocation("view_to_world"), 1, GL_FALSE,
                     glm::value_ptr(to_world));
  glUniform3fv(programs_.composite->uniformLocation("light_view"), 1, glm::value_ptr(light_view));
  glUniform3fv(programs_.composite->uniformLocation("light_power"), 1, glm::value_ptr(power));
  programs_.composite->setUniformValue("light_is_spot", light.type == Light::Type::Spot ? 1 : 0);
  glUniform3fv(programs_.composite->uniformLocation("spot_axis_view"), 1, glm::value_ptr(axis));
  programs_.composite->setUniformValue("spot_cos",
                                       QVector2D(std::cos(glm::radians(light.spot_inner_deg)),
                                                 std::cos(glm::radians(light.spot_outer_deg))));
  programs_.composite->setUniformValue("far_plane", 2.0f * camera_.scene_diagonal());
  programs_.composite->setUniformValue("shadow_bias", 0.003f * camera_.scene_diagonal());
  programs_.composite->setUniformValue("pcf_radius", 0.006f);
  programs_.composite->setUniformValue("show_direct", direct);
  programs_.composite->setUniformValue("show_indirect", indirect);
  programs_.composite->setUniformValue("use_ao", ao);
  programs_.composite->setUniformValue("exposure", exposure);
  programs_.composite->setUniformValue("linear_output", linear);
  programs_.composite->setUniformValue("background", QVector3D(0.12f, 0.12f, 0.13f));
  glBindVertexArray(empty_vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void PreviewWidget::paintGL() {
  const double now = static_cast<double>(clock_.nsecsElapsed()) * 1e-9;
  if (last_paint_ >= 0.0) {
    const double interval = now - last_paint_;
    // Smoothed over about ten frames; a pause (nothing to redraw) is no frame time.
    if (interval <= 1.0)
      mean_interval_ = mean_interval_ <= 0.0 ? interval : 0.9 * mean_interval_ + 0.1 * interval;
  }
  last_paint_ = now;
  try {
    render(defaultFramebufferObject());
  } catch (const std::exception& e) {
    gl_error_ = QString::fromStdString(e.what());
  }
  if (overlay_) draw_overlay();
}

void PreviewWidget::draw_overlay() {
  QPainter painter(this);
  painter.setRenderHint(QPainter::TextAntialiasing);
  QStringList lines;
  if (!gl_error_.isEmpty()) {
    lines << tr("OpenGL: %1").arg(gl_error_);
  } else if (!lighting_) {
    lines << tr("No bake loaded");
  } else {
    lines << (mean_interval_ > 0.0 ? tr("%1 fps (%2 ms per frame)")
                                         .arg(1.0 / mean_interval_, 0, 'f', 1)
                                         .arg(1e3 * mean_interval_, 0, 'f', 1)
                                   : tr("-- fps"));
    lines << tr("solve %1 ms (frame graph %2, to vertices %3) on the %4")
                 .arg(last_solve_ms(), 0, 'f', 1)
                 .arg(last_frame_graph_ms(), 0, 'f', 1)
                 .arg(last_transfer_ms(), 0, 'f', 1)
                 .arg(solve_on_worker_ ? tr("worker") : tr("UI thread"));
    lines << tr("%1 patches, %2 vertices, T b: %3")
                 .arg(lighting_->patch_count())
                 .arg(vertex_count())
                 .arg(QString::fromStdString(lighting_->multiply_name()));
    lines << tr("light '%1' at (%2, %3, %4)%5")
                 .arg(QString::fromStdString(lighting_->light().name))
                 .arg(light_position_.x, 0, 'f', 2)
                 .arg(light_position_.y, 0, 'f', 2)
                 .arg(light_position_.z, 0, 'f', 2)
                 .arg(solved_light_ == light_position_ ? QString() : tr(" (solving)"));
    lines << tr("direct %1  indirect %2  AO %3")
                 .arg(passes_.direct ? "on" : "off")
                 .arg(passes_.indirect ? "on" : "off")
                 .arg(passes_.ao ? "on" : "off");
  }
  const QFontMetrics metrics(painter.font());
  const int line = metrics.height();
  int text_width = 0;
  for (const QString& l : lines) text_width = std::max(text_width, metrics.horizontalAdvance(l));
  painter.fillRect(QRect(4, 4, text_width + 12, line * lines.size() + 8), QColor(0, 0, 0, 150));
  painter.setPen(Qt::white);
  for (int k = 0; k < lines.size(); ++k)
    painter.drawText(10, 8 + line * k + metrics.ascent(), lines[k]);
}

QImage PreviewWidget::render_image() { return grabFramebuffer(); }

double PreviewWidget::measure_frame_ms(int frames) {
  if (frames < 1 || !isValid()) return 0.0;
  makeCurrent();
  QElapsedTimer timer;
  timer.start();
  for (int k = 0; k < frames; ++k) {
    shadow_dirty_ = true;  // as while the light is dragged: the shadow map too
    render(defaultFramebufferObject());
    glFinish();
  }
  const double ms = static_cast<double>(timer.nsecsElapsed()) * 1e-6 / frames;
  doneCurrent();
  mean_interval_ = 1e-3 * ms;  // the overlay shows the measured rate
  last_paint_ = -1.0;
  return ms;
}

}  // namespace bounce::views
