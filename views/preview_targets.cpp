#include "preview_targets.h"

#include <algorithm>
#include <iterator>
#include <string>
#include <utility>

#include "bounce/error.h"

namespace bounce::views {

GLuint PreviewTargets::texture(GLenum internal, GLenum format, int width, int height) {
  GLuint t = 0;
  gl_.glGenTextures(1, &t);
  gl_.glBindTexture(GL_TEXTURE_2D, t);
  gl_.glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(internal), width, height, 0, format,
                   GL_FLOAT, nullptr);
  gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}

void PreviewTargets::check_complete(const char* what) {
  if (gl_.glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error("preview", std::string("the ") + what + " framebuffer is incomplete");
}

void PreviewTargets::ensure_size(int width, int height) {
  if (width == width_ && height == height_ && gbuffer_fbo_) return;
  release();
  gl_.glGenFramebuffers(1, &gbuffer_fbo_);
  gl_.glBindFramebuffer(GL_FRAMEBUFFER, gbuffer_fbo_);
  GLenum attachments[kGbufferTargets];
  for (int k = 0; k < kGbufferTargets; ++k) {
    gbuffer_textures_[k] = texture(GL_RGBA16F, GL_RGBA, width, height);
    attachments[k] = static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + k);
    gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, attachments[k], GL_TEXTURE_2D, gbuffer_textures_[k],
                               0);
  }
  gl_.glDrawBuffers(kGbufferTargets, attachments);
  gl_.glGenRenderbuffers(1, &gbuffer_depth_);
  gl_.glBindRenderbuffer(GL_RENDERBUFFER, gbuffer_depth_);
  gl_.glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  gl_.glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                gbuffer_depth_);
  check_complete("G-buffer");

  for (auto [fbo, tex] :
       {std::pair{&ao_fbo_, &ao_texture_}, std::pair{&blur_fbo_, &blur_texture_}}) {
    *tex = texture(GL_R16F, GL_RED, width, height);
    gl_.glGenFramebuffers(1, fbo);
    gl_.glBindFramebuffer(GL_FRAMEBUFFER, *fbo);
    gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, *tex, 0);
    check_complete("occlusion");
  }
  width_ = width;
  height_ = height;
}

void PreviewTargets::release() {
  if (gbuffer_fbo_) gl_.glDeleteFramebuffers(1, &gbuffer_fbo_);
  if (gbuffer_depth_) gl_.glDeleteRenderbuffers(1, &gbuffer_depth_);
  gl_.glDeleteTextures(kGbufferTargets, gbuffer_textures_);  // zeros are ignored
  if (ao_fbo_) gl_.glDeleteFramebuffers(1, &ao_fbo_);
  if (blur_fbo_) gl_.glDeleteFramebuffers(1, &blur_fbo_);
  if (ao_texture_) gl_.glDeleteTextures(1, &ao_texture_);
  if (blur_texture_) gl_.glDeleteTextures(1, &blur_texture_);
  gbuffer_fbo_ = gbuffer_depth_ = ao_fbo_ = blur_fbo_ = ao_texture_ = blur_texture_ = 0;
  std::fill(std::begin(gbuffer_textures_), std::end(gbuffer_textures_), 0u);
  width_ = height_ = 0;
}

}  // namespace bounce::views
