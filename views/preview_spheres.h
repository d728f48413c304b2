#pragma once
// Spheres the live preview draws into its G-buffer beside the scene, each
// lit by its own SH L2 irradiance (runtime/light_probes.h): the light
// probes' overlay, and the probe-lit sphere that stands for a moving object.
// One unit-sphere mesh drawn instanced, one instance per sphere.
#include <array>
#include <vector>

#include <QOpenGLFunctions_3_3_Core>
#include <QOpenGLShaderProgram>
#include <glm/glm.hpp>

#include "bounce/relight.h"

namespace bounce::views {

struct SphereInstance {
  glm::vec3 centre{0.0f};
  float radius = 1.0f;
  // The moving sphere reflects the composite's direct light and the SH
  // irradiance (times the occlusion) as a surface of this albedo does.
  glm::vec3 albedo{0.0f};
  // A probe of the overlay shows its SH irradiance as is, the light a
  // white surface would send out under it, whatever the passes.
  bool probe = false;
  std::array<glm::vec3, kShCoefficients> sh{};
};

class PreviewSpheres {
 public:
  // gl: the functions of the context every call below runs in (current).
  explicit PreviewSpheres(QOpenGLFunctions_3_3_Core& gl) : gl_(gl) {}
  PreviewSpheres(const PreviewSpheres&) = delete;
  PreviewSpheres& operator=(const PreviewSpheres&) = delete;

  // Replaces the instances (the mesh is made on first use).
  void set(const std::vector<SphereInstance>& spheres);
  // Draws every instance with `program` (preview_sphere.vert/.frag), whose
  // view and projection the caller has set.
  void draw(QOpenGLShaderProgram& program);
  // Deletes the GL objects; needs the context current.
  void release();

 private:
  void make_mesh();

  QOpenGLFunctions_3_3_Core& gl_;
  GLuint vao_ = 0, mesh_vbo_ = 0, index_ebo_ = 0, instance_vbo_ = 0;
  GLsizei index_count_ = 0, instances_ = 0;
};

}  // namespace bounce::views
