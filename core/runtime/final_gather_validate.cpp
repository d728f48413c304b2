// Whether a final gather's rows, sources and weights agree with each other
// and with the bake's patch and sample counts. Kept apart from building a
// gather: a bake folder's reader checks a stored gather with this alone,
// without the ray tracer that builds one.
#include "runtime/final_gather.h"

#include <cmath>
#include <string>

#include "base/error.h"

namespace bounce {

void FinalGather::validate(const std::string& what) const {
  if (first.empty() || first.front() != 0 || first.back() != source.size() ||
      source.size() != weight.size())
    throw Error(what, "row offsets do not match the " + std::to_string(source.size()) + " entries");
  if (cluster_of_patch.size() != patches || cluster_share.size() != patches)
    throw Error(what, "one cluster and share per patch expected");
  for (std::size_t p = 0; p < patches; ++p)
    if (cluster_of_patch[p] >= clusters || !(cluster_share[p] >= 0.0f && cluster_share[p] <= 1.0f))
      throw Error(what, "patch " + std::to_string(p) + "'s cluster or share is out of range");
  if (near.normal.size() != near.size() || near.albedo.size() != near.size() ||
      near.patch.size() != near.size())
    throw Error(what, "near sources need a position, normal, albedo and patch each");
  if (near.size() > 0 && samples == 0)
    throw Error(what, "near sources without the bake's sample count");
  for (std::size_t k = 0; k < near.size(); ++k) {
    const glm::vec3 v[3] = {near.position[k], near.normal[k], near.albedo[k]};
    for (const glm::vec3& x : v)
      if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z))
        throw Error(what, "near source " + std::to_string(k) + " is not finite");
    if (near.patch[k] >= patches)
      throw Error(what, "near source " + std::to_string(k) + " names patch " +
                            std::to_string(near.patch[k]) + " of " + std::to_string(patches));
  }
  if (!seen_first.empty()) {
    if (seen_first.size() != patches + 1 || seen_first.front() != 0 ||
        seen_first.back() != seen_sample.size() || seen_sample.size() != seen_weight.size())
      throw Error(what, "the seen weights' row starts do not match their " +
                            std::to_string(seen_sample.size()) + " entries and " +
                            std::to_string(patches) + " patches");
    if (samples == 0) throw Error(what, "seen weights without the bake's sample count");
    for (std::size_t p = 0; p < patches; ++p) {
      if (seen_first[p + 1] < seen_first[p])
        throw Error(what, "the seen weights' row starts decrease at patch " + std::to_string(p));
      double total = 0.0;
      for (std::uint32_t k = seen_first[p]; k < seen_first[p + 1]; ++k) {
        if (seen_sample[k] >= samples || !(seen_weight[k] >= 0.0f && seen_weight[k] <= 1.0f))
          throw Error(what, "patch " + std::to_string(p) +
                                "'s seen weights name a sample out of range or a weight "
                                "outside [0, 1]");
        total += seen_weight[k];
      }
      if (seen_first[p + 1] > seen_first[p] && std::abs(total - 1.0) > 1e-3)
        throw Error(what, "patch " + std::to_string(p) + "'s seen weights sum to " +
                              std::to_string(total) + ", not 1");
    }
  }
  if (near.spot_count != spots())
    throw Error(what, "the near sources end in " + std::to_string(near.spot_count) +
                          " spots, the spots' row starts name " + std::to_string(spots()));
  if (!spot_first.empty()) {
    if (spot_first.size() != samples + 1 || spot_first.front() != 0 ||
        spot_first.back() != spot_weight.size() || spot_first.back() > near.size())
      throw Error(what, "the spots' row starts do not match their " +
                            std::to_string(spot_weight.size()) + " weights, " +
                            std::to_string(samples) + " samples and " +
                            std::to_string(near.size()) + " near sources");
    for (std::size_t s = 0; s < samples; ++s) {
      if (spot_first[s + 1] < spot_first[s])
        throw Error(what, "the spots' row starts decrease at sample " + std::to_string(s));
      double total = 0.0;
      for (std::uint32_t k = spot_first[s]; k < spot_first[s + 1]; ++k) {
        if (!(spot_weight[k] >= 0.0f && spot_weight[k] <= 1.0f))
          throw Error(what, "sample " + std::to_string(s) + " has a spot weight outside [0, 1]");
        total += spot_weight[k];
      }
      if (spot_first[s + 1] > spot_first[s] && std::abs(total - 1.0) > 1e-3)
        throw Error(what, "sample " + std::to_string(s) + "'s spot weights sum to " +
                              std::to_string(total) + ", not 1");
    }
  }
  for (std::size_t i = 0; i + 1 < first.size(); ++i) {
    if (first[i + 1] < first[i])
      throw Error(what, "row offsets decrease at point " + std::to_string(i));
    double total = 0.0;
    for (std::uint64_t k = first[i]; k < first[i + 1]; ++k) {
      if (source[k] >= patches + clusters + samples + near.size())
        throw Error(what, "point " + std::to_string(i) + " gathers from source " +
                              std::to_string(source[k]) + " of " +
                              std::to_string(patches + clusters + samples + near.size()));
      if (!(weight[k] >= 0.0f && weight[k] <= 1.0f))
        throw Error(what, "point " + std::to_string(i) + " has a weight outside [0, 1]");
      total += weight[k];
    }
    if (total > 1.0 + 1e-4)
      throw Error(what, "point " + std::to_string(i) + "'s weights sum to " +
                            std::to_string(total) + " > 1");
  }
}

}  // namespace bounce
