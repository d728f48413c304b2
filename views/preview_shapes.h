#pragma once
// Shapes the live preview draws into its G-buffer beside the scene, each
// lit by its own SH L2 irradiance (runtime/light_probes.h): the light
// probes' overlay (small spheres), and the object that stands for a moving
// thing (a sphere, or a mesh the user loads). One mesh of unit size drawn
// instanced, one instance per shape.
#include <array>
#include <vector>

#include <QOpenGLFunctions_3_3_Core>
#include <QOpenGLShaderProgram>
#include <glm/glm.hpp>

#include "bounce/relight.h"

namespace bounce::views {

struct ShapeInstance {
  glm::vec3 centre{0.0f};
  float radius = 1.0f;  // the mesh's unit is scaled to this
  // The object reflects the composite's direct light and the SH irradiance
  // (times the occlusion) as a surface of this albedo does.
  glm::vec3 albedo{0.0f};
  // A probe of the overlay shows its SH irradiance as is, the light a
  // white surface would send out under it, whatever the passes.
  bool probe = false;
  std::array<glm::vec3, kShCoefficients> sh{};
};

class PreviewShapes {
 public:
  // gl: the functions of the context every call below runs in (current).
  explicit PreviewShapes(QOpenGLFunctions_3_3_Core& gl) : gl_(gl) {}
  PreviewShapes(const PreviewShapes&) = delete;
  PreviewShapes& operator=(const PreviewShapes&) = delete;

  // The mesh every instance draws: triangles as three corners each, within
  // the unit ball, with a unit normal per corner. Empty: the unit sphere.
  void set_mesh(std::vector<glm::vec3> corners, std::vector<glm::vec3> normals);
  // Replaces the instances.
  void set(const std::vector<ShapeInstance>& shapes);
  // Draws every instance with `program` (preview_shape.vert/.frag), whose
  // view and projection the caller has set.
  void draw(QOpenGLShaderProgram& program);
  // Deletes the GL objects; needs the context current. The mesh is kept
  // and uploaded again on the next set().
  void release();

 private:
  void upload_mesh();

  QOpenGLFunctions_3_3_Core& gl_;
  std::vector<glm::vec3> corners_, normals_;
  GLuint vao_ = 0, mesh_vbo_ = 0, instance_vbo_ = 0;
  GLsizei corner_count_ = 0, instances_ = 0;
};

}  // namespace bounce::views
