#pragma once
// How far light probes' SH (runtime/light_probes.h) are from the path
// tracer: at each measured probe, the irradiance the SH gives for the six
// axis normals against the reference's indirect irradiance at the same
// point and normal (light reflected at least once, what the SH holds).
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "base/progress.h"
#include "reference/path_tracer.h"

namespace bounce {

struct ProbeReferenceError {
  std::size_t probes_measured = 0;
  int samples = 0;  // the reference's paths per point and normal
  // sqrt(sum (probe - ref)^2 / sum ref^2) over points, normals and channels.
  double relative_rmse = 0.0;
  // What the reference's own noise adds to it: sqrt(sum var / sum ref^2).
  double reference_noise = 0.0;
  // The probes' own error: relative_rmse with the reference's noise taken
  // out in quadrature (the two are independent).
  double noise_corrected_rmse = 0.0;
  // sum probe / sum ref.
  double level = 0.0;
};

// Which of `count` probes are measured: every k-th, k chosen so that at
// most `max_probes` are.
std::vector<std::size_t> probe_reference_choice(std::size_t count, std::size_t max_probes);

// The points the reference is estimated at for probes at `positions`: each
// with the six axis normals (probe p's normal k at 6 p + k).
std::vector<ReferencePoint> probe_reference_points(const std::vector<glm::vec3>& positions);

// `sh` (kShCoefficients per position) against `reference` at `points`
// (probe_reference_points). Throws bounce::Error when the sizes
// differ.
ProbeReferenceError compare_probe_sh(const std::vector<ReferencePoint>& points,
                                     const PointReference& reference,
                                     const std::vector<glm::vec3>& sh);

// Measures the probes probe_reference_choice picks.
// `sh` holds kShCoefficients per probe. Throws bounce::Error when the sizes
// differ; Cancelled when progress asks to stop.
ProbeReferenceError probe_reference_error(const ReferencePathTracer& reference,
                                          const std::vector<glm::vec3>& positions,
                                          const std::vector<glm::vec3>& sh, std::size_t max_probes,
                                          Progress* progress = nullptr);

}  // namespace bounce
