#include "runtime/gather_clusters.h"

#include <cmath>
#include <map>
#include <tuple>

namespace bounce {

void make_clusters(const std::vector<Patch>& patches, const VoxelGrid& grid, int block,
                   FinalGather& g) {
  std::map<std::tuple<int, int, int, int, int>, std::uint32_t> index;
  g.cluster_of_patch.resize(patches.size());
  g.cluster_share.resize(patches.size());
  std::vector<double> area;
  for (std::size_t p = 0; p < patches.size(); ++p) {
    const glm::ivec3 c = grid.cell_of(patches[p].position) / block;
    const glm::vec3 a = glm::abs(patches[p].normal);
    const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    // Emitters are clusters of their own: a lamp's light differs from the
    // surface it hangs on (and a point light next to a lamp makes its patches
    // the brightest of the scene).
    const bool emits = glm::dot(patches[p].emission, glm::vec3(1.0f)) > 0.0f;
    const int direction = 2 * axis + (patches[p].normal[axis] < 0.0f ? 1 : 0) + (emits ? 6 : 0);
    const int layer = static_cast<int>(std::floor(
        (patches[p].position[axis] - grid.bounds().lo[axis]) / (0.25f * grid.cell_size())));
    const auto [it, added] = index.try_emplace({c.x, c.y, c.z, direction, layer},
                                               static_cast<std::uint32_t>(index.size()));
    if (added) area.push_back(0.0);
    g.cluster_of_patch[p] = it->second;
    area[it->second] += patches[p].area;
  }
  g.clusters = index.size();
  for (std::size_t p = 0; p < patches.size(); ++p) {
    const double a = area[g.cluster_of_patch[p]];
    g.cluster_share[p] = a > 0.0 ? static_cast<float>(patches[p].area / a) : 0.0f;
  }
}

void weigh_by_seen_rays(const SurfacePatchLookup& lookup, const std::vector<std::uint64_t>& seen,
                        const std::vector<std::uint64_t>& cluster_rays, FinalGather& g) {
  std::vector<std::uint64_t> patch_total(g.patches, 0);
  std::vector<std::uint32_t> patch_entries(g.patches, 0);
  for (std::size_t s = 0; s < seen.size(); ++s)
    if (seen[s] > 0) {
      const auto p = static_cast<std::size_t>(lookup.patch_of(static_cast<std::uint32_t>(s)));
      patch_total[p] += seen[s];
      ++patch_entries[p];
    }
  g.seen_first.assign(g.patches + 1, 0);
  for (std::size_t p = 0; p < g.patches; ++p)
    g.seen_first[p + 1] = g.seen_first[p] + patch_entries[p];
  g.seen_sample.resize(g.seen_first.back());
  g.seen_weight.resize(g.seen_first.back());
  std::vector<std::uint32_t> at(g.seen_first.begin(), g.seen_first.end() - 1);
  for (std::size_t s = 0; s < seen.size(); ++s)
    if (seen[s] > 0) {
      const auto p = static_cast<std::size_t>(lookup.patch_of(static_cast<std::uint32_t>(s)));
      g.seen_sample[at[p]] = static_cast<std::uint32_t>(s);
      g.seen_weight[at[p]++] =
          static_cast<float>(static_cast<double>(seen[s]) / static_cast<double>(patch_total[p]));
    }
  std::vector<std::uint64_t> cluster_total(g.clusters, 0);
  for (std::size_t p = 0; p < g.patches; ++p)
    cluster_total[g.cluster_of_patch[p]] += cluster_rays[p];
  for (std::size_t p = 0; p < g.patches; ++p)
    if (const std::uint64_t t = cluster_total[g.cluster_of_patch[p]]; t > 0)
      g.cluster_share[p] =
          static_cast<float>(static_cast<double>(cluster_rays[p]) / static_cast<double>(t));
}

}  // namespace bounce
