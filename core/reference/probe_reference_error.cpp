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

std::vector<std::size_t> probe_reference_choice(std::size_t count, std::size_t max_probes) {
  std::vector<std::size_t> chosen;
  if (count == 0 || max_probes == 0) return chosen;
  const std::size_t stride = (count + max_probes - 1) / max_probes;
  for (std::size_t p = 0; p < count; p += stride) chosen.push_back(p);
  return chosen;
}

std::vector<ReferencePoint> probe_reference_points(const std::vector<glm::vec3>& positions) {
  std::vector<ReferencePoint> points;
  points.reserve(positions.size() * kAxes);
  for (const glm::vec3& at : positions)
    for (std::size_t k = 0; k < kAxes; ++k)
      points.push_back({at, probe_directions()[k], glm::vec3(0.0f), glm::vec3(0.0f)});
  return points;
}

ProbeReferenceError compare_probe_sh(const std::vector<ReferencePoint>& points,
                                     const PointReference& ref, const std::vector<glm::vec3>& sh) {
  if (sh.size() * kAxes != points.size() * kShCoefficients ||
      ref.indirect_irradiance.size() != points.size())
    throw Error("light probes", std::to_string(sh.size()) + " SH coefficients and " +
                                    std::to_string(ref.indirect_irradiance.size()) +
                                    " reference values for " + std::to_string(points.size()) +
                                    " points");
  ProbeReferenceError out;
  out.samples = ref.samples;
  out.probes_measured = points.size() / kAxes;
  double diff_sq = 0.0, ref_sq = 0.0, var = 0.0, probe_sum = 0.0, ref_sum = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const glm::vec3 e = sh_irradiance(sh.data() + (i / kAxes) * kShCoefficients, points[i].normal);
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

ProbeReferenceError probe_reference_error(const ReferencePathTracer& reference,
                                          const std::vector<glm::vec3>& positions,
                                          const std::vector<glm::vec3>& sh, std::size_t max_probes,
                                          Progress* progress) {
  if (sh.size() != positions.size() * kShCoefficients)
    throw Error("light probes", std::to_string(sh.size()) + " SH coefficients for " +
                                    std::to_string(positions.size()) + " probes");
  std::vector<glm::vec3> chosen, chosen_sh;
  for (const std::size_t p : probe_reference_choice(positions.size(), max_probes)) {
    chosen.push_back(positions[p]);
    chosen_sh.insert(chosen_sh.end(), sh.begin() + static_cast<std::ptrdiff_t>(p * kShCoefficients),
                     sh.begin() + static_cast<std::ptrdiff_t>((p + 1) * kShCoefficients));
  }
  if (chosen.empty()) {
    ProbeReferenceError out;
    out.samples = reference.settings().samples;
    return out;
  }
  const std::vector<ReferencePoint> points = probe_reference_points(chosen);
  return compare_probe_sh(points, reference.estimate_points(points, progress), chosen_sh);
}

}  // namespace bounce
