#pragma once
// Patches: clusters of samples inside one voxel, with no geometry of their
// own: a position (area-weighted centroid, for display and
// transfer), a normal, an albedo, an emission and an area. Each keeps the list
// of its member samples, from which form factors are computed.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "patches/samples.h"

namespace bounce {

struct Patch {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec3 albedo;
  glm::vec3 emission;
  float area;
  std::uint32_t voxel;
  std::uint32_t mesh;  // mesh of the member carrying the most area
};

struct PatchSet {
  std::vector<Patch> patches;
  // Members of patch p: member_samples[member_first[p] .. member_first[p+1]).
  std::vector<std::uint32_t> member_first;
  std::vector<std::uint32_t> member_samples;
  // Seen weights (empty: none): each member's share of the patch's first-hit
  // light, by how often the rays of the bake's final gather landed on it
  // instead of by its area (runtime/seen_first_hit.h). Aligned with
  // member_samples; a patch whose members' weights are all 0 uses its area
  // mean.
  std::vector<float> member_seen_weight;

  std::size_t size() const { return patches.size(); }
  std::size_t member_count(std::size_t p) const { return member_first[p + 1] - member_first[p]; }

  // Builds a patch from the given samples with the virtual-patch merge rules:
  // area-weighted normal (normalised), colour and emission; areas add.
  void add_patch(const std::vector<Sample>& samples, const std::vector<std::uint32_t>& members);
  // Keeps only the patches for which keep[p] is true, in order.
  void keep_only(const std::vector<bool>& keep);
};

}  // namespace bounce
