#include "reference/probe_wall_agreement.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/constants.hpp>

#include "base/error.h"
#include "runtime/light_probes.h"

namespace bounce {

namespace {

constexpr float kFacing = 0.95f;     // cos of about 18 degrees
constexpr float kFlatness = 0.02f;   // of the reach: how far the plane may bend
constexpr float kLift = 0.02f;       // of the reach: where the ray along the normal starts
constexpr int kPlaneDirections = 8;  // tangent directions tested

// Two unit vectors spanning the plane normal to n.
void tangents(const glm::vec3& n, glm::vec3& u, glm::vec3& v) {
  const glm::vec3 a = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  u = glm::normalize(glm::cross(n, a));
  v = glm::cross(n, u);
}

bool on_flat_open_wall(const RayTracer& tracer, const glm::vec3& x, const glm::vec3& n,
                       float reach) {
  if (tracer.intersect(x + kLift * reach * n, n, 0.0f, reach).hit) return false;
  // From `reach` above the vertex, at 45 degrees to the wall: a plane bent
  // by d moves the hit by about 1.4 d.
  const glm::vec3 o = x + reach * n;
  glm::vec3 u, v;
  tangents(n, u, v);
  for (int k = 0; k < kPlaneDirections; ++k) {
    const float a = glm::two_pi<float>() * static_cast<float>(k) / kPlaneDirections;
    const glm::vec3 d = x + reach * (std::cos(a) * u + std::sin(a) * v) - o;
    const float length = glm::length(d);
    const Hit h = tracer.intersect(o, d / length, 0.0f, 2.0f * length);
    if (!h.hit || std::abs(glm::dot(h.geometric_normal, n)) < kFacing) return false;
    if (std::abs(h.t - length) > 1.5f * kFlatness * reach) return false;
  }
  return true;
}

}  // namespace

std::vector<std::uint32_t> open_wall_vertices(const RayTracer& tracer, const LitMesh& mesh,
                                              float reach, std::size_t max) {
  std::vector<std::uint32_t> open;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    if (on_flat_open_wall(tracer, mesh.positions[i], mesh.normals[i], reach))
      open.push_back(static_cast<std::uint32_t>(i));
  if (max == 0 || open.size() <= max) return open;
  const std::size_t step = (open.size() + max - 1) / max;
  std::vector<std::uint32_t> kept;
  for (std::size_t i = 0; i < open.size(); i += step) kept.push_back(open[i]);
  return kept;
}

std::vector<glm::vec3> probe_positions_off(const LitMesh& mesh,
                                           const std::vector<std::uint32_t>& vertices,
                                           float offset) {
  std::vector<glm::vec3> out;
  out.reserve(vertices.size());
  for (const std::uint32_t v : vertices)
    out.push_back(mesh.positions.at(v) + offset * mesh.normals.at(v));
  return out;
}

ProbeWallAgreement probe_wall_agreement(const LitMesh& mesh,
                                        const std::vector<glm::vec3>& vertex_irradiance,
                                        const std::vector<std::uint32_t>& vertices,
                                        const std::vector<glm::vec3>& probe_sh) {
  if (probe_sh.size() != vertices.size() * kShCoefficients)
    throw Error("light probes", "the SH holds " + std::to_string(probe_sh.size()) +
                                    " coefficients for " + std::to_string(vertices.size()) +
                                    " probes");
  if (vertex_irradiance.size() != mesh.positions.size())
    throw Error("lit mesh", "the irradiance does not match its vertices");
  ProbeWallAgreement out;
  double diff2 = 0.0, wall2 = 0.0, probe_sum = 0.0, wall_sum = 0.0;
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    const glm::vec3 wall = vertex_irradiance.at(vertices[k]);
    const glm::vec3 probe =
        sh_irradiance(&probe_sh[k * kShCoefficients], mesh.normals[vertices[k]]);
    for (int c = 0; c < 3; ++c) {
      diff2 += std::pow(static_cast<double>(probe[c]) - wall[c], 2.0);
      wall2 += static_cast<double>(wall[c]) * wall[c];
      probe_sum += probe[c];
      wall_sum += wall[c];
    }
    ++out.spots;
  }
  if (wall2 > 0.0) out.relative_rmse = std::sqrt(diff2 / wall2);
  if (wall_sum > 0.0) out.level = probe_sum / wall_sum;
  return out;
}

}  // namespace bounce
