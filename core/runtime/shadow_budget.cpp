#include "runtime/shadow_budget.h"

#include <algorithm>

#include "base/error.h"

namespace bounce {

namespace {

// What decides which points a light's rays reach unblocked, and which rays
// it takes: not its colour or intensity.
bool same_rays(const Light& a, const Light& b) {
  return a.type == b.type && a.position == b.position && a.direction == b.direction &&
         a.spot_inner_deg == b.spot_inner_deg && a.spot_outer_deg == b.spot_outer_deg;
}

}  // namespace

ShadowBudget::ShadowBudget(int frames) : frames_(static_cast<std::size_t>(std::max(frames, 1))) {
  if (frames < 1) throw Error("shadow budget", "frames must be at least 1");
}

void ShadowBudget::begin_frame(const void* points, std::size_t batches,
                               const std::vector<Light>& lights) {
  bool all = points != points_ || batches != batches_ || lights.size() != lights_.size();
  for (std::size_t l = 0; !all && l < lights.size(); ++l) all = lights[l].type != lights_[l].type;
  if (all) {
    points_ = points;
    batches_ = batches;
    slice_.assign(lights.size(), kAll);
    pending_.assign(lights.size(), 0);
    cursor_.assign(lights.size(), 0);
    visibility_.assign(lights.size(), {});
  } else {
    for (std::size_t l = 0; l < lights.size(); ++l) {
      if (!same_rays(lights[l], lights_[l])) pending_[l] = static_cast<int>(frames_);
      if (pending_[l] > 0) {
        slice_[l] = cursor_[l];  // with k = 1, always 0: every batch
        cursor_[l] = (cursor_[l] + 1) % static_cast<int>(frames_);
        --pending_[l];
      } else {
        slice_[l] = kNone;
      }
    }
  }
  lights_ = lights;
  traced_batches_ = 0;
  for (std::size_t l = 0; l < lights.size(); ++l)
    for (std::size_t b = 0; b < batches; ++b) traced_batches_ += traced(l, b) ? 1 : 0;
}

bool ShadowBudget::settled() const {
  return std::all_of(pending_.begin(), pending_.end(), [](int p) { return p == 0; });
}

std::vector<std::uint8_t>& ShadowBudget::visibility_of(std::size_t l, std::size_t points) {
  std::vector<std::uint8_t>& v = visibility_[l];
  if (v.size() != points) v.assign(points, 1);
  return v;
}

}  // namespace bounce
