#include "patches/patch_set.h"

#include <map>

namespace bounce {

void PatchSet::add_patch(const std::vector<Sample>& samples,
                         const std::vector<std::uint32_t>& members) {
  if (member_first.empty()) member_first.push_back(0);
  Patch p{};
  glm::vec3 normal_sum(0.0f);
  std::map<std::uint32_t, float> area_of_mesh;
  for (std::uint32_t s : members) {
    const Sample& x = samples[s];
    p.area += x.area;
    p.position += x.area * x.position;
    normal_sum += x.area * x.normal;
    p.albedo += x.area * x.albedo;
    p.emission += x.area * x.emission;
    area_of_mesh[x.mesh] += x.area;
    member_samples.push_back(s);
  }
  const float inv = p.area > 0.0f ? 1.0f / p.area : 0.0f;
  p.position *= inv;
  p.albedo *= inv;
  p.emission *= inv;
  const float len = glm::length(normal_sum);
  p.normal = len > 0.0f ? normal_sum / len : samples[members.front()].normal;
  p.voxel = samples[members.front()].voxel;
  float best = -1.0f;
  for (const auto& [mesh, area] : area_of_mesh)
    if (area > best) {
      best = area;
      p.mesh = mesh;
    }
  patches.push_back(p);
  member_first.push_back(static_cast<std::uint32_t>(member_samples.size()));
}

void PatchSet::keep_only(const std::vector<bool>& keep) {
  PatchSet out;
  out.member_first.push_back(0);
  for (std::size_t p = 0; p < patches.size(); ++p) {
    if (!keep[p]) continue;
    out.patches.push_back(patches[p]);
    out.member_samples.insert(out.member_samples.end(), member_samples.begin() + member_first[p],
                              member_samples.begin() + member_first[p + 1]);
    if (!member_seen_weight.empty())
      out.member_seen_weight.insert(out.member_seen_weight.end(),
                                    member_seen_weight.begin() + member_first[p],
                                    member_seen_weight.begin() + member_first[p + 1]);
    out.member_first.push_back(static_cast<std::uint32_t>(out.member_samples.size()));
  }
  *this = std::move(out);
}

}  // namespace bounce
