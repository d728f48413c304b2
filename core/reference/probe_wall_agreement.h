#pragma once
// Whether a light probe and the wall it stands on agree: a probe just off a
// lit-mesh vertex on a flat open wall, its SH evaluated for the wall's
// normal, against the irradiance the vertex itself gathers. The two come
// from different gathers (the probe's 14 hemispheres fitted with 9
// coefficients, the vertex's own cosine rays, near sources and spots), so
// where nothing but the open room is in front of the wall their difference
// is what SH L2 cannot hold: this checks the probes against the light
// people see on the walls next to them, without a path tracer.
//
// A vertex is on a flat open wall when, seen from just in front of it,
// nothing stands within `reach` along its normal and rays aimed at eight
// points of its tangent plane `reach` away meet that plane, facing the
// same way: no corner, edge or object within reach.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "raytrace/ray_tracer.h"
#include "runtime/mesh_transfer.h"

namespace bounce {

// Vertices of `mesh` on flat open walls, every k-th of them so that at most
// `max` are returned, in vertex order.
std::vector<std::uint32_t> open_wall_vertices(const RayTracer& tracer, const LitMesh& mesh,
                                              float reach, std::size_t max);

// Where probes stand for `vertices`: `offset` in front of each, along its
// normal (above the tracer's epsilon, so that its rays leave the wall).
std::vector<glm::vec3> probe_positions_off(const LitMesh& mesh,
                                           const std::vector<std::uint32_t>& vertices,
                                           float offset);

struct ProbeWallAgreement {
  std::size_t spots = 0;  // vertices compared
  // sqrt(sum (probe - wall)^2 / sum wall^2) over vertices and channels.
  double relative_rmse = 0.0;
  double level = 0.0;  // sum probe / sum wall
};

// `probe_sh`: kShCoefficients irradiance coefficients (runtime/light_probes.h)
// per entry of `vertices`, of probes at probe_positions_off;
// `vertex_irradiance`: the indirect irradiance per vertex of `mesh` in the
// same frame. Throws bounce::Error when the sizes do not match.
ProbeWallAgreement probe_wall_agreement(const LitMesh& mesh,
                                        const std::vector<glm::vec3>& vertex_irradiance,
                                        const std::vector<std::uint32_t>& vertices,
                                        const std::vector<glm::vec3>& probe_sh);

}  // namespace bounce
