// The preview's OpenGL resources: the context's programs, the shadow cube
// and the SSAO noise made once; the mesh and its per-vertex indirect light
// uploaded when the bake or the frame changes; all released with the context.
#include <cstdint>
#include <exception>
#include <random>
#include <vector>

#include <QOpenGLShaderProgram>

#include "bounce/scene.h"
#include "preview_corners.h"
#include "preview_lighting.h"
#include "preview_programs.h"
#include "preview_widget.h"

namespace bounce::views {

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
  probe_spheres_.release();
  object_.release();
  shapes_dirty_ = true;
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

}  // namespace bounce::views
