#include <atomic>

#include "patches/samples.h"

namespace bounce {

std::size_t apply_texture_albedo(const Scene& scene, const Voxelization& vox, SampleSet& set,
                                 Progress* progress) {
  if (scene.triangle_uv.empty()) return 0;
  const std::size_t n = set.samples.size();
  if (progress) progress->begin_stage("texture albedo", n);
  std::atomic<std::size_t> changed{0};
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t si = 0; si < static_cast<std::int64_t>(n); ++si) {
    const auto s = static_cast<std::size_t>(si);
    if (progress && (s & 1023) == 0) {
      if (progress->should_stop()) continue;
      progress->advance(std::min<std::size_t>(1024, n - s));
    }
    bool any = false;
    for (std::uint32_t c = set.carried_first[s]; c < set.carried_first[s + 1] && !any; ++c)
      any = scene.textured(vox.parts[set.carried[c].part].triangle);
    if (!any) continue;
    glm::dvec3 sum(0.0);
    double total = 0.0;
    for (std::uint32_t c = set.carried_first[s]; c < set.carried_first[s + 1]; ++c) {
      const CarriedArea& a = set.carried[c];
      const glm::vec3 albedo = scene.mean_albedo(
          vox.parts[a.part].triangle, &set.carried_vertices[a.first_vertex], a.vertex_count);
      sum += static_cast<double>(a.area) * glm::dvec3(albedo);
      total += static_cast<double>(a.area);
    }
    if (total > 0.0) {
      set.samples[s].albedo = glm::vec3(sum / total);
      changed.fetch_add(1, std::memory_order_relaxed);
    }
  }
  if (progress) {
    progress->check();
    progress->end_stage();
  }
  return changed.load();
}

}  // namespace bounce
