#include "runtime/area_light_cache.h"

#include <algorithm>

namespace bounce {

namespace {

bool same_light(const AreaLight& a, const AreaLight& b) {
  return a.triangle == b.triangle && a.v0 == b.v0 && a.e1 == b.e1 && a.e2 == b.e2 &&
         a.normal == b.normal && a.exitance == b.exitance && a.area == b.area &&
         a.two_sided == b.two_sided && a.emission_texture == b.emission_texture &&
         a.emission_factor == b.emission_factor && a.uv == b.uv;
}

}  // namespace

const std::vector<glm::vec3>& AreaLightCache::irradiance(const void* points, std::size_t count,
                                                         const std::vector<AreaLight>& area,
                                                         int strata, const Compute& compute) {
  const bool same = valid_ && points == points_ && count == count_ && strata == strata_ &&
                    area.size() == area_.size() &&
                    std::equal(area.begin(), area.end(), area_.begin(), same_light);
  if (!same) {
    // Invalid until `compute` returns: an exception leaves nothing half kept.
    valid_ = false;
    compute(irradiance_);
    points_ = points;
    count_ = count;
    area_ = area;
    strata_ = strata;
    valid_ = true;
    ++computed_;
  }
  return irradiance_;
}

}  // namespace bounce
