// The preview's frame: the light's shadow cube, the render passes into the
// targets, the exposure calibrated on the first frame, the composite, the
// overlay, and the frame read back or timed.
#include <algorithm>
#include <cmath>
#include <exception>
#include <vector>

#include <QElapsedTimer>
#include <QFontMetrics>
#include <QImage>
#include <QOpenGLShaderProgram>
#include <QPainter>
#include <QVector2D>
#include <QVector3D>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "bounce/pictures.h"
#include "bounce/scene.h"
#include "preview_lighting.h"
#include "preview_programs.h"
#include "preview_widget.h"

namespace bounce::views {

namespace {

// The six faces of a cube map as OpenGL orders them, with the up vectors
// its face layout implies.
constexpr glm::vec3 kCubeForward[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                       {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
constexpr glm::vec3 kCubeUp[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1},
                                  {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};

}  // namespace

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

// The G-buffer: position, normal, albedo, emission and indirect light per
// pixel.
void PreviewWidget::render_gbuffer(const glm::mat4& view, const glm::mat4& projection, int w,
                                   int h) {
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
  draw_shapes(view, projection);
  glDisable(GL_DEPTH_TEST);
}

// Screen-space occlusion of the G-buffer, then its blur.
void PreviewWidget::render_occlusion(const glm::mat4& projection, int w, int h) {
  auto bind = [this](int unit, GLenum kind, GLuint texture) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
    glBindTexture(kind, texture);
  };
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
  render_gbuffer(view, projection, w, h);
  glBindVertexArray(empty_vao_);
  // 2-3. Occlusion and its blur (only when they are shown).
  const bool ao = passes_.ao && passes_.indirect;
  if (ao) render_occlusion(projection, w, h);

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
    if (has_probes())
      lines << tr("%1 light probes, %2 ms (gather, SH fit, sphere blend)")
                   .arg(probe_count())
                   .arg(1e3 * probe_seconds_, 0, 'f', 2);
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
