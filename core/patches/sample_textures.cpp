#include <atomic>

#include "patches/samples.h"

namespace bounce {

std::size_t apply_surface_textures(const Scene& scene, const Voxelization& vox, SampleSet& set,
                                   Progress* progress) {
  const bool coloured = scene.has_vertex_colours();
  if (scene.triangle_uv.empty() && !coloured) return 0;
  const std::size_t n = set.samples.size();
  if (progress) progress->begin_stage("surface textures", n);
  std::atomic<std::size_t> changed{0};
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t si = 0; si < static_cast<std::int64_t>(n); ++si) {
    const auto s = static_cast<std::size_t>(si);
    if (progress && (s & 1023) == 0) {
      if (progress->should_stop()) continue;
      progress->advance(std::min<std::size_t>(1024, n - s));
    }
    bool albedo = false, emission = false;
    for (std::uint32_t c = set.carried_first[s]; c < set.carried_first[s + 1]; ++c) {
      albedo = albedo || coloured || scene.textured(vox.parts[set.carried[c].part].triangle);
      emission = emission || scene.emission_textured(vox.parts[set.carried[c].part].triangle);
    }
    if (!albedo && !emission) continue;
    glm::dvec3 albedo_sum(0.0), emission_sum(0.0);
    double total = 0.0;
    for (std::uint32_t c = set.carried_first[s]; c < set.carried_first[s + 1]; ++c) {
      const CarriedArea& a = set.carried[c];
      const std::uint32_t tri = vox.parts[a.part].triangle;
      const glm::vec3* polygon = &set.carried_vertices[a.first_vertex];
      const auto area = static_cast<double>(a.area);
      if (albedo) albedo_sum += area * glm::dvec3(scene.mean_albedo(tri, polygon, a.vertex_count));
      if (emission)
        emission_sum += area * glm::dvec3(scene.mean_emission(tri, polygon, a.vertex_count));
      total += area;
    }
    if (total > 0.0) {
      if (albedo) set.samples[s].albedo = glm::vec3(albedo_sum / total);
      if (emission) set.samples[s].emission = glm::vec3(emission_sum / total);
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
