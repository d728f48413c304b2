#include "formfactor/far_field.h"

#include <numbers>
#include <string>

#include "base/error.h"

namespace bounce {

namespace {

// As far_exchange in form_factors.cpp, operation for operation, so the sums
// are the ones compute_form_factors forms.
float exchange(const glm::vec3& pa, const glm::vec3& na, float aa, const glm::vec3& pb,
               const glm::vec3& nb, float ab) {
  const glm::vec3 d = pb - pa;
  const float r2 = glm::dot(d, d);
  const float fa = glm::dot(na, d), fb = -glm::dot(nb, d);
  if (fa <= 0.0f || fb <= 0.0f || !(r2 > 0.0f)) return 0.0f;
  return aa * ab * fa * fb / (std::numbers::pi_v<float> * r2 * r2);
}

}  // namespace

void validate(const FarPoints& points) {
  if (points.offsets.empty()) {
    if (!points.positions.empty() || !points.normals.empty() || !points.areas.empty())
      throw Error("far field", "points without patch offsets");
    return;
  }
  if (points.offsets.front() != 0) throw Error("far field", "the first patch offset is not 0");
  for (std::size_t p = 0; p + 1 < points.offsets.size(); ++p)
    if (points.offsets[p + 1] < points.offsets[p])
      throw Error("far field", "patch offsets decrease at patch " + std::to_string(p));
  const std::size_t m = points.offsets.back();
  if (points.positions.size() != m || points.normals.size() != m || points.areas.size() != m)
    throw Error("far field",
                "the point arrays do not have offsets.back() = " + std::to_string(m) + " entries");
}

std::vector<float> far_field_sums(const FarPoints& points) {
  validate(points);
  const std::size_t n = points.patches();
  std::vector<float> sums(n * n, 0.0f);
  const glm::vec3* pos = points.positions.data();
  const glm::vec3* nrm = points.normals.data();
  const float* area = points.areas.data();
  const std::uint32_t* off = points.offsets.data();
  // Rows are uneven (row p has n - p pairs): hand them out dynamically.
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t pi = 0; pi < static_cast<std::int64_t>(n); ++pi) {
    const auto p = static_cast<std::size_t>(pi);
    for (std::size_t q = p; q < n; ++q) {
      float sum = 0.0f;
      for (std::uint32_t i = off[p]; i < off[p + 1]; ++i)
        for (std::uint32_t j = off[q]; j < off[q + 1]; ++j) {
          if (q == p && i == j) continue;  // a point does not exchange with itself
          const float w = exchange(pos[i], nrm[i], area[i], pos[j], nrm[j], area[j]);
          if (w <= 0.0f) continue;
          sum += w;
        }
      sums[p * n + q] = sum;
    }
  }
  return sums;
}

}  // namespace bounce
