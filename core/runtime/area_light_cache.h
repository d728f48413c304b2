#pragma once
// Area lights are scene triangles: while they and the points they light stay
// as they were, their light at those points is the same every frame, so a
// relighter works it out once and keeps it. Moving a point, spot or
// directional light then costs nothing here; changing any area light (its
// corners, exitance or texture) or the number of rays works it out again.
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "runtime/area_lights.h"

namespace bounce {

class AreaLightCache {
 public:
  // The irradiance per point from `area` with `strata` x `strata` rays: the
  // kept one when the points (`points`, the address of their first
  // position, and their count), lights and strata are the ones it was made
  // for, else what `compute` writes (into a vector it sizes), kept for next
  // time.
  using Compute = std::function<void(std::vector<glm::vec3>&)>;
  const std::vector<glm::vec3>& irradiance(const void* points, std::size_t count,
                                           const std::vector<AreaLight>& area, int strata,
                                           const Compute& compute);
  // How many times the light was worked out (not taken from the cache).
  std::size_t computed() const { return computed_; }

 private:
  bool valid_ = false;
  const void* points_ = nullptr;
  std::size_t count_ = 0;
  std::vector<AreaLight> area_;
  int strata_ = 0;
  std::vector<glm::vec3> irradiance_;
  std::size_t computed_ = 0;
};

}  // namespace bounce
