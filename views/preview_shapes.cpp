#include "preview_shapes.h"

#include <cmath>
#include <cstddef>
#include <utility>

#include <glm/gtc/constants.hpp>

namespace bounce::views {

namespace {

// A latitude-longitude unit sphere: fine enough that the SH irradiance,
// evaluated per vertex, shows no facets (SH L2 varies slowly).
constexpr int kRings = 16, kSegments = 24;

std::vector<glm::vec3> unit_sphere() {
  const auto point = [](int r, int s) {
    const float theta = glm::pi<float>() * static_cast<float>(r) / kRings;
    const float phi = glm::two_pi<float>() * static_cast<float>(s) / kSegments;
    return glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                     std::sin(theta) * std::sin(phi));
  };
  std::vector<glm::vec3> corners;
  for (int r = 0; r < kRings; ++r)
    for (int s = 0; s < kSegments; ++s)
      for (const auto& [dr, ds] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}})
        corners.push_back(point(r + dr, s + ds));
  return corners;
}

// Per-vertex attributes: position, normal. Per instance: centre and radius,
// albedo and the probe flag, 9 SH coefficients.
constexpr GLuint kPosition = 0, kNormal = 12, kFirstInstanceAttribute = 1;
constexpr std::size_t kInstanceFloats = 8 + 3 * kShCoefficients;

}  // namespace

void PreviewShapes::set_mesh(std::vector<glm::vec3> corners, std::vector<glm::vec3> normals) {
  corners_ = std::move(corners);
  normals_ = std::move(normals);
  if (vao_) upload_mesh();
}

void PreviewShapes::upload_mesh() {
  if (!vao_) {
    gl_.glGenVertexArrays(1, &vao_);
    gl_.glGenBuffers(1, &mesh_vbo_);
    gl_.glGenBuffers(1, &instance_vbo_);
  }
  // The sphere's normal at a point is the point.
  const std::vector<glm::vec3> corners = corners_.empty() ? unit_sphere() : corners_;
  const std::vector<glm::vec3>& normals = corners_.empty() ? corners : normals_;
  std::vector<glm::vec3> data;
  data.reserve(2 * corners.size());
  for (std::size_t i = 0; i < corners.size(); ++i)
    data.insert(data.end(), {corners[i], normals[i]});
  corner_count_ = static_cast<GLsizei>(corners.size());
  gl_.glBindVertexArray(vao_);
  gl_.glBindBuffer(GL_ARRAY_BUFFER, mesh_vbo_);
  gl_.glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(glm::vec3)),
                   data.data(), GL_STATIC_DRAW);
  const auto stride = static_cast<GLsizei>(2 * sizeof(glm::vec3));
  gl_.glEnableVertexAttribArray(kPosition);
  gl_.glVertexAttribPointer(kPosition, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
  gl_.glEnableVertexAttribArray(kNormal);
  gl_.glVertexAttribPointer(kNormal, 3, GL_FLOAT, GL_FALSE, stride,
                            reinterpret_cast<const void*>(sizeof(glm::vec3)));

  gl_.glBindBuffer(GL_ARRAY_BUFFER, instance_vbo_);
  const auto instance_stride = static_cast<GLsizei>(kInstanceFloats * sizeof(float));
  const auto attribute = [&](GLuint index, GLint size, std::size_t first_float) {
    gl_.glEnableVertexAttribArray(index);
    gl_.glVertexAttribPointer(index, size, GL_FLOAT, GL_FALSE, instance_stride,
                              reinterpret_cast<const void*>(first_float * sizeof(float)));
    gl_.glVertexAttribDivisor(index, 1);
  };
  attribute(kFirstInstanceAttribute, 4, 0);      // centre, radius
  attribute(kFirstInstanceAttribute + 1, 4, 4);  // albedo, probe
  for (std::size_t j = 0; j < kShCoefficients; ++j)
    attribute(kFirstInstanceAttribute + 2 + static_cast<GLuint>(j), 3, 8 + 3 * j);
  gl_.glBindVertexArray(0);
}

void PreviewShapes::set(const std::vector<ShapeInstance>& shapes) {
  if (!vao_) upload_mesh();
  std::vector<float> data;
  data.reserve(shapes.size() * kInstanceFloats);
  for (const ShapeInstance& s : shapes) {
    data.insert(data.end(), {s.centre.x, s.centre.y, s.centre.z, s.radius, s.albedo.x, s.albedo.y,
                             s.albedo.z, s.probe ? 1.0f : 0.0f});
    for (const glm::vec3& c : s.sh) data.insert(data.end(), {c.x, c.y, c.z});
  }
  gl_.glBindBuffer(GL_ARRAY_BUFFER, instance_vbo_);
  gl_.glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(float)),
                   data.data(), GL_DYNAMIC_DRAW);
  instances_ = static_cast<GLsizei>(shapes.size());
}

void PreviewShapes::draw(QOpenGLShaderProgram& program) {
  if (instances_ == 0) return;
  program.bind();
  gl_.glBindVertexArray(vao_);
  gl_.glDrawArraysInstanced(GL_TRIANGLES, 0, corner_count_, instances_);
  gl_.glBindVertexArray(0);
}

void PreviewShapes::release() {
  if (vao_) gl_.glDeleteVertexArrays(1, &vao_);
  for (GLuint* buffer : {&mesh_vbo_, &instance_vbo_})
    if (*buffer) gl_.glDeleteBuffers(1, buffer);
  vao_ = mesh_vbo_ = instance_vbo_ = 0;
  corner_count_ = instances_ = 0;
}

}  // namespace bounce::views
