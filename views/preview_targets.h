#pragma once
// The live preview's off-screen render targets at one size (views/
// preview_widget.h lists the passes): the G-buffer, five RGBA16F colour
// targets in the order of preview_gbuffer.frag's outputs plus a depth buffer,
// and the occlusion map and its blur, R16F each. RGBA16F throughout the
// G-buffer: the paper's RGB16F is not required to be colour-renderable in
// OpenGL 3.3, RGBA16F is.
#include <QOpenGLFunctions_3_3_Core>

namespace bounce::views {

class PreviewTargets {
 public:
  static constexpr int kGbufferTargets = 5;  // position, normal, albedo, emission, indirect

  // gl: the functions of the context every call below runs in (current).
  explicit PreviewTargets(QOpenGLFunctions_3_3_Core& gl) : gl_(gl) {}
  PreviewTargets(const PreviewTargets&) = delete;
  PreviewTargets& operator=(const PreviewTargets&) = delete;

  // Makes the targets at width x height unless they already are that size.
  // Throws bounce::Error when the driver reports a framebuffer incomplete.
  void ensure_size(int width, int height);
  // Deletes every target (size 0 x 0). Needs the context current: the owner
  // calls it before the context goes.
  void release();

  GLuint gbuffer_fbo() const { return gbuffer_fbo_; }
  GLuint gbuffer_texture(int k) const { return gbuffer_textures_[k]; }
  GLuint ao_fbo() const { return ao_fbo_; }
  GLuint ao_texture() const { return ao_texture_; }
  GLuint blur_fbo() const { return blur_fbo_; }
  GLuint blur_texture() const { return blur_texture_; }

 private:
  GLuint texture(GLenum internal, GLenum format, int width, int height);
  void check_complete(const char* what);

  QOpenGLFunctions_3_3_Core& gl_;
  GLuint gbuffer_fbo_ = 0, gbuffer_depth_ = 0;
  GLuint gbuffer_textures_[kGbufferTargets] = {0, 0, 0, 0, 0};
  GLuint ao_fbo_ = 0, ao_texture_ = 0, blur_fbo_ = 0, blur_texture_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace bounce::views
