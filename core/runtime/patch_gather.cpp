#include "runtime/patch_gather.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "base/error.h"

namespace bounce {

PatchGather::PatchGather(const std::vector<Patch>& patches, const std::vector<glm::vec3>& light,
                         const TransferGrid& grid, const RayTracer* tracer, GatherSettings settings)
    : light_(light), grid_(grid), tracer_(tracer), settings_(settings) {
  if (light.size() != patches.size())
    throw Error("light transfer", "got light for " + std::to_string(light.size()) +
                                      " patches, the bake has " + std::to_string(patches.size()));
  for (std::size_t p = 0; p < light.size(); ++p)
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(light[p][c]))
        throw Error("light transfer", "light of patch " + std::to_string(p) + " is not finite");
  if (settings_.visibility && tracer_ == nullptr)
    throw Error("light transfer", "visibility needs a ray tracer");
  if (!(settings_.radius_cells > 0.0f && settings_.radius_cells <= 1.0f) ||
      settings_.normal_power < 0)
    throw Error("light transfer",
                "kernel radius must be in (0, 1] voxel and the normal power at least 0");

  position_.reserve(patches.size());
  normal_.reserve(patches.size());
  for (const Patch& p : patches) {
    position_.push_back(p.position);
    normal_.push_back(p.normal);
  }
  std::vector<std::uint64_t> keys(patches.size());
  for (std::size_t p = 0; p < patches.size(); ++p)
    keys[p] = key(grid_.cell_of(patches[p].position));
  sorted_.resize(patches.size());
  std::iota(sorted_.begin(), sorted_.end(), 0u);
  std::stable_sort(sorted_.begin(), sorted_.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
  for (std::size_t i = 0; i < sorted_.size();) {
    std::size_t j = i;
    while (j < sorted_.size() && keys[sorted_[j]] == keys[sorted_[i]]) ++j;
    cells_[keys[sorted_[i]]] = {static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j - i)};
    i = j;
  }
}

std::uint64_t PatchGather::key(const glm::ivec3& c) const {
  return (static_cast<std::uint64_t>(c.z) * static_cast<std::uint64_t>(grid_.dims.y) +
          static_cast<std::uint64_t>(c.y)) *
             static_cast<std::uint64_t>(grid_.dims.x) +
         static_cast<std::uint64_t>(c.x);
}

void PatchGather::collect(const glm::vec3& x, const glm::vec3& n, const glm::ivec3& c, int shell,
                          float reach, std::vector<Candidate>& out) const {
  const float inv_reach2 = 1.0f / (reach * reach);
  const float inv_cell = 1.0f / grid_.cell_size;
  for (int dz = -shell; dz <= shell; ++dz)
    for (int dy = -shell; dy <= shell; ++dy)
      for (int dx = -shell; dx <= shell; ++dx) {
        if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) != shell) continue;
        const glm::ivec3 q = c + glm::ivec3(dx, dy, dz);
        if (glm::any(glm::lessThan(q, glm::ivec3(0))) ||
            glm::any(glm::greaterThanEqual(q, grid_.dims)))
          continue;
        const auto it = cells_.find(key(q));
        if (it == cells_.end()) continue;
        for (std::uint32_t i = it->second.first; i < it->second.first + it->second.second; ++i) {
          const std::uint32_t p = sorted_[i];
          const float agree = glm::dot(n, normal_[p]);
          if (!(agree > 0.0f)) continue;
          const glm::vec3 d = (x - position_[p]) * inv_cell;
          const float falloff = 1.0f - glm::dot(d, d) * inv_reach2;
          if (!(falloff > 0.0f)) continue;
          const float w =
              falloff * falloff * std::pow(agree, static_cast<float>(settings_.normal_power));
          if (w > 0.0f) out.push_back({p, w});
        }
      }
}

GatherResult PatchGather::gather(const glm::vec3& x, const glm::vec3& n) const {
  GatherResult r;
  const glm::ivec3 c = grid_.cell_of(x);
  std::vector<Candidate> candidates;
  std::vector<ShadowRay> rays;
  std::vector<std::uint8_t> blocked;
  // Shells 0 and 1 make the 3x3x3 block, which holds every patch within one
  // voxel; shells 0 to 2 with twice the reach are the one widening.
  for (int pass = 0; pass < 2; ++pass) {
    const float reach = settings_.radius_cells * static_cast<float>(pass + 1);
    for (int shell = 0; shell <= pass + 1; ++shell) collect(x, n, c, shell, reach, candidates);
    if (settings_.visibility && !candidates.empty()) {
      const glm::vec3 origin = x + settings_.point_offset_cells * grid_.cell_size * n;
      const float clearance = settings_.point_clearance_cells * grid_.cell_size;
      rays.clear();
      for (const Candidate& cand : candidates) {
        const glm::vec3 end = position_[cand.patch] +
                              settings_.patch_offset_cells * grid_.cell_size * normal_[cand.patch];
        const glm::vec3 d = end - origin;
        const float length = glm::length(d);
        const float t_near = length > 0.0f ? std::min(0.5f, clearance / length) : 0.0f;
        rays.push_back({origin, d, t_near, 1.0f});
      }
      blocked.assign(rays.size(), 0);
      tracer_->occluded(rays.data(), rays.size(), blocked.data());
      r.rays += static_cast<std::uint32_t>(rays.size());
      for (std::size_t i = 0; i < candidates.size(); ++i)
        if (blocked[i]) candidates[i].weight = 0.0f;
    }
    double sum_w = 0.0;
    glm::dvec3 sum(0.0);
    for (const Candidate& cand : candidates) {
      if (cand.weight <= 0.0f) continue;
      sum_w += cand.weight;
      sum += static_cast<double>(cand.weight) * glm::dvec3(light_[cand.patch]);
    }
    if (sum_w > 0.0) {
      r.light = glm::vec3(sum / sum_w);
      r.weight = static_cast<float>(sum_w);
      return r;
    }
    if (pass == 1) break;
    r.widened = true;
    candidates.clear();
  }
  return r;
}

}  // namespace bounce
