#include "preview_material_images.h"

namespace bounce::views {

// The core's decoded images, uploaded as they are: the albedo and emissive
// textures in linear RGB and the normal map's stored values, each with the
// core's own MIP pyramid (each level half the last, as OpenGL expects), the
// alpha mask's coverage at its one level. All are stored row 0 first, the
// top of the image, which is v = 1: the shaders look up (u, 1 - v).
// R11F_G11F_B10F keeps linear light in 4 bytes a texel, so a scene with many
// large textures fits; a normal map needs more than its 6 bits of mantissa
// (a degree of tilt is 0.009 of a channel): RGB16F; a mask needs 8 bits.
PreviewMaterialImages::Images PreviewMaterialImages::upload(const Scene& scene,
                                                            std::size_t material) {
  Images images;
  if (scene.triangle_uv.empty()) return images;
  const Material& m = scene.materials[material];
  gl_.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  images.texture = upload_texture(m.texture.get(), GL_R11F_G11F_B10F);
  images.emission = upload_texture(m.emission_texture.get(), GL_R11F_G11F_B10F);
  images.normal_map = upload_texture(m.normal_map.get(), GL_RGB16F);
  if (const AlphaMask* a = m.alpha_mask.get(); a != nullptr && !a->values.empty()) {
    GLuint& name = uploaded_[a];
    if (name == 0) {
      // No MIP levels: the core cuts with the full-resolution mask, and
      // averaged coverage would fade holes away with distance.
      name = make(GL_LINEAR);
      gl_.glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, a->width, a->height, 0, GL_RED, GL_FLOAT,
                       a->values.data());
      gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    }
    images.mask = name;
  }
  gl_.glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  gl_.glBindTexture(GL_TEXTURE_2D, 0);
  return images;
}

void PreviewMaterialImages::release() {
  if (!names_.empty()) gl_.glDeleteTextures(static_cast<GLsizei>(names_.size()), names_.data());
  names_.clear();
  uploaded_.clear();
}

GLuint PreviewMaterialImages::make(GLint min_filter) {
  GLuint name = 0;
  gl_.glGenTextures(1, &name);
  gl_.glBindTexture(GL_TEXTURE_2D, name);
  gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, min_filter);
  gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);  // the core's wrapping
  gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  names_.push_back(name);
  return name;
}

GLuint PreviewMaterialImages::upload_texture(const Texture* t, GLint format) {
  if (t == nullptr || t->levels.empty()) return 0;
  GLuint& name = uploaded_[t];
  if (name == 0) {
    name = make(GL_LINEAR_MIPMAP_LINEAR);
    for (std::size_t level = 0; level < t->levels.size(); ++level) {
      const Texture::Level& l = t->levels[level];
      gl_.glTexImage2D(GL_TEXTURE_2D, static_cast<GLint>(level), format, l.width, l.height, 0,
                       GL_RGB, GL_FLOAT, l.texels.data());
    }
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL,
                        static_cast<GLint>(t->levels.size()) - 1);
  }
  return name;
}

}  // namespace bounce::views
