#include "preview_spheres.h"

#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/gtc/constants.hpp>

namespace bounce::views {

namespace {

// A latitude-longitude unit sphere: fine enough that the SH irradiance,
// evaluated per vertex, shows no facets (SH L2 varies slowly).
constexpr int kRings = 16, kSegments = 24;

// Instance attributes: centre and radius, albedo and the probe flag, 9 SH
// coefficients.
constexpr GLuint kFirstInstanceAttribute = 1;
constexpr std::size_t kInstanceFloats = 8 + 3 * kShCoefficients;

}  // namespace

void PreviewSpheres::make_mesh() {
  std::vector<glm::vec3> points;
  for (int r = 0; r <= kRings; ++r) {
    const float theta = glm::pi<float>() * static_cast<float>(r) / kRings;
    for (int s = 0; s <= kSegments; ++s) {
      const float phi = glm::two_pi<float>() * static_cast<float>(s) / kSegments;
      points.emplace_back(std::sin(theta) * std::cos(phi), std::cos(theta),
                          std::sin(theta) * std::sin(phi));
    }
  }
  std::vector<std::uint32_t> indices;
  const auto at = [](int r, int s) { return static_cast<std::uint32_t>(r * (kSegments + 1) + s); };
  for (int r = 0; r < kRings; ++r)
    for (int s = 0; s < kSegments; ++s)
      for (const std::uint32_t i :
           {at(r, s), at(r + 1, s), at(r + 1, s + 1), at(r, s), at(r + 1, s + 1), at(r, s + 1)})
        indices.push_back(i);
  index_count_ = static_cast<GLsizei>(indices.size());

  gl_.glGenVertexArrays(1, &vao_);
  gl_.glBindVertexArray(vao_);
  gl_.glGenBuffers(1, &mesh_vbo_);
  gl_.glBindBuffer(GL_ARRAY_BUFFER, mesh_vbo_);
  gl_.glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(points.size() * sizeof(glm::vec3)),
                   points.data(), GL_STATIC_DRAW);
  gl_.glEnableVertexAttribArray(0);
  gl_.glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
  gl_.glGenBuffers(1, &index_ebo_);
  gl_.glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, index_ebo_);
  gl_.glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                   static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)), indices.data(),
                   GL_STATIC_DRAW);

  gl_.glGenBuffers(1, &instance_vbo_);
  gl_.glBindBuffer(GL_ARRAY_BUFFER, instance_vbo_);
  const auto stride = static_cast<GLsizei>(kInstanceFloats * sizeof(float));
  const auto attribute = [&](GLuint index, GLint size, std::size_t first_float) {
    gl_.glEnableVertexAttribArray(index);
    gl_.glVertexAttribPointer(index, size, GL_FLOAT, GL_FALSE, stride,
                              reinterpret_cast<const void*>(first_float * sizeof(float)));
    gl_.glVertexAttribDivisor(index, 1);
  };
  attribute(kFirstInstanceAttribute, 4, 0);      // centre, radius
  attribute(kFirstInstanceAttribute + 1, 4, 4);  // albedo, probe
  for (std::size_t j = 0; j < kShCoefficients; ++j)
    attribute(kFirstInstanceAttribute + 2 + static_cast<GLuint>(j), 3, 8 + 3 * j);
  gl_.glBindVertexArray(0);
}

void PreviewSpheres::set(const std::vector<SphereInstance>& spheres) {
  if (!vao_) make_mesh();
  std::vector<float> data;
  data.reserve(spheres.size() * kInstanceFloats);
  for (const SphereInstance& s : spheres) {
    data.insert(data.end(), {s.centre.x, s.centre.y, s.centre.z, s.radius, s.albedo.x, s.albedo.y,
                             s.albedo.z, s.probe ? 1.0f : 0.0f});
    for (const glm::vec3& c : s.sh) data.insert(data.end(), {c.x, c.y, c.z});
  }
  gl_.glBindBuffer(GL_ARRAY_BUFFER, instance_vbo_);
  gl_.glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(float)),
                   data.data(), GL_DYNAMIC_DRAW);
  instances_ = static_cast<GLsizei>(spheres.size());
}

void PreviewSpheres::draw(QOpenGLShaderProgram& program) {
  if (instances_ == 0) return;
  program.bind();
  gl_.glBindVertexArray(vao_);
  gl_.glDrawElementsInstanced(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr, instances_);
  gl_.glBindVertexArray(0);
}

void PreviewSpheres::release() {
  if (vao_) gl_.glDeleteVertexArrays(1, &vao_);
  for (GLuint* buffer : {&mesh_vbo_, &index_ebo_, &instance_vbo_})
    if (*buffer) gl_.glDeleteBuffers(1, buffer);
  vao_ = mesh_vbo_ = index_ebo_ = instance_vbo_ = 0;
  index_count_ = instances_ = 0;
}

}  // namespace bounce::views
