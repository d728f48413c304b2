#include "reference/probe_reference_error.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/error.h"
#include "runtime/light_probes.h"

namespace bounce {

namespace {
constexpr std::size_t kAxes = 6;  // the first six probe_directions()
}  // namespace

ProbeReferenceError probe_reference_error(const ReferencePathTracer& reference,
                                          const std::vector<glm::vec3>& positions,
                                          const std::vector<glm::vec3>& sh, std::size_t max_probes,
                                          Progress* progress) {
  if (sh.size() != positions.size() * kShCoefficients)
    throw Error("light probes", std::to_string(sh.size()) + " SH coefficients for " +
                                    std::to_string(positions.size()) + " probes");
  ProbeReferenceError out;
  out.samples = reference.settings().samples;
  if (positions.empty() || max_probes == 0) return out;
  const std::size_t stride = (positions.size() + max_probes - 1) / max_probes;
  std::vector<ReferencePoint> points;
  std::vector<std::size_t> probe_of_point;
  for (std::size_t p = 0; p < positions.size(); p += stride)
    for (std::size_t k = 0; k < kAxes; ++k) {
      points.push_back({positions[p], probe_directions()[k], glm::vec3(0.0f), glm::vec3(0.0f)});
      probe_of_point.push_back(p);
    }
  out.probes_measured = points.size() / kAxes;
  const PointReference ref = reference.estimate_points(points, progress);
  double diff_sq = 0.0, ref_sq = 0.0, var = 0.0, probe_sum = 0.0, ref_sum = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const glm::vec3 e =
        sh_irradiance(sh.data() + probe_of_point[i] * kShCoefficients, points[i].normal);
    for (int c = 0; c < 3; ++c) {
      const double r = ref.indirect_irradiance[i][c];
      diff_sq += (e[c] - r) * (e[c] - r);
      ref_sq += r * r;
      var += ref.indirect_variance[i][c];
      probe_sum += e[c];
      ref_sum += r;
    }
  }
  if (ref_sq <= 0.0) return out;
  out.relative_rmse = std::sqrt(diff_sq / ref_sq);
  out.reference_noise = std::sqrt(var / ref_sq);
  out.noise_corrected_rmse = std::sqrt(std::max(0.0, (diff_sq - var) / ref_sq));
  out.level = ref_sum > 0.0 ? probe_sum / ref_sum : 0.0;
  return out;
}

}  // namespace bounce
