#include "report/exact_patch_light.h"

namespace bounce {

ExactPatchLight exact_patch_indirect(const ReferencePathTracer& pt, const SampleSet& samples,
                                     const PatchSet& patches, const ReferenceCache* cache,
                                     Progress* progress) {
  std::vector<ReferencePoint> points;
  points.reserve(samples.samples.size());
  for (const Sample& s : samples.samples)
    points.push_back({s.position, s.normal, s.albedo, glm::vec3(0.0f)});
  const PointReference ref = cached_reference_points(pt, points, cache, progress);
  ExactPatchLight out;
  out.indirect.assign(patches.size(), glm::vec3(0.0f));
  out.variance.assign(patches.size(), glm::vec3(0.0f));
  out.reflected.assign(patches.size(), glm::vec3(0.0f));
  for (std::size_t p = 0; p < patches.size(); ++p) {
    glm::dvec3 sum(0.0), var(0.0), reflected(0.0);
    double area = 0.0;
    for (std::uint32_t k = patches.member_first[p]; k < patches.member_first[p + 1]; ++k) {
      const std::uint32_t si = patches.member_samples[k];
      const Sample& s = samples.samples[si];
      const glm::dvec3 weight = static_cast<double>(s.area) * glm::dvec3(s.albedo);
      sum += weight * glm::dvec3(ref.indirect_irradiance[si]);
      reflected += weight * glm::dvec3(ref.direct_irradiance[si]);
      var += weight * weight * glm::dvec3(ref.indirect_variance[si]);
      area += s.area;
    }
    if (area > 0.0) {
      out.indirect[p] = glm::vec3(sum / area);
      out.reflected[p] = glm::vec3((sum + reflected) / area);
      out.variance[p] = glm::vec3(var / (area * area));
    }
  }
  return out;
}

}  // namespace bounce
