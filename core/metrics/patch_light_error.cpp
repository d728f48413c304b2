#include "metrics/patch_light_error.h"

#include <cmath>
#include <string>

#include "base/error.h"
#include "metrics/vertex_metrics.h"
#include "runtime/dense_transport.h"

namespace bounce {

double area_weighted_relative_rms(const std::vector<float>& area,
                                  const std::vector<glm::vec3>& test,
                                  const std::vector<glm::vec3>& exact) {
  if (test.size() != exact.size() || area.size() != exact.size())
    throw Error("patch light error",
                "areas, test and exact light differ in size (" + std::to_string(area.size()) +
                    ", " + std::to_string(test.size()) + ", " + std::to_string(exact.size()) + ")");
  double err2 = 0.0, ref2 = 0.0;
  for (std::size_t p = 0; p < exact.size(); ++p) {
    const glm::dvec3 d = glm::dvec3(test[p]) - glm::dvec3(exact[p]);
    err2 += area[p] * glm::dot(d, d);
    ref2 += area[p] * glm::dot(glm::dvec3(exact[p]), glm::dvec3(exact[p]));
  }
  return ref2 > 0.0 ? std::sqrt(err2 / ref2) : 0.0;
}

PatchLightError patch_light_error(const std::vector<const float*>& exact,
                                  const std::vector<const float*>& approx, std::size_t n,
                                  const std::array<int, 3>& channel_of_rgb,
                                  const std::vector<glm::vec3>& b, const std::vector<float>& area) {
  PatchLightError e;
  dense_indirect(exact, n, channel_of_rgb, b, e.exact);
  dense_indirect(approx, n, channel_of_rgb, b, e.approx);
  e.relative = vertex_relative_errors(e.approx, e.exact);
  e.rel_rms = area_weighted_relative_rms(area, e.approx, e.exact);
  return e;
}

}  // namespace bounce
