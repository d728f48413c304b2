#pragma once
// The live preview's material images on the GPU (views/preview_widget.h
// lists the passes): each material's albedo texture, alpha mask, normal map
// and emissive texture as the core decoded them, uploaded once each however
// many materials share them, and deleted together.
#include <cstddef>
#include <map>
#include <vector>

#include <QOpenGLFunctions_3_3_Core>

#include "bounce/scene.h"

namespace bounce::views {

class PreviewMaterialImages {
 public:
  // The OpenGL images of one material (0: it has none of that kind).
  struct Images {
    GLuint texture = 0, mask = 0, normal_map = 0, emission = 0;
  };

  // gl: the functions of the context every call below runs in (current).
  explicit PreviewMaterialImages(QOpenGLFunctions_3_3_Core& gl) : gl_(gl) {}
  PreviewMaterialImages(const PreviewMaterialImages&) = delete;
  PreviewMaterialImages& operator=(const PreviewMaterialImages&) = delete;

  // Uploads what material `material` of `scene` needs and has not been
  // uploaded yet; none for a scene without texture coordinates. The scene
  // must stay the same until release().
  Images upload(const Scene& scene, std::size_t material);
  // Deletes every image. Needs the context current: the owner calls it
  // before the context goes, and before the images of another scene.
  void release();

 private:
  GLuint make(GLint min_filter);
  GLuint upload_texture(const Texture* t, GLint format);

  QOpenGLFunctions_3_3_Core& gl_;
  std::map<const void*, GLuint> uploaded_;  // a texture shared by materials is uploaded once
  std::vector<GLuint> names_;               // every image made, each once
};

}  // namespace bounce::views
