// Whether a final gather's rows, sources and weights agree with each other
// and with the bake's patch and sample counts. Kept apart from building a
// gather: a bake folder's reader checks a stored gather with this alone,
// without the ray tracer that builds one.
#include "runtime/final_gather.h"

#include <cmath>
#include <string>

#include "base/error.h"

namespace bounce {

namespace {

// The row offsets, and one cluster and share per patch.
void check_rows_and_clusters(const FinalGather& g, const std::string& what) {
  if (g.first.empty() || g.first.front() != 0 || g.first.back() != g.source.size() ||
      g.source.size() != g.weight.size())
    throw Error(what,
                "row offsets do not match the " + std::to_string(g.source.size()) + " entries");
  if (g.cluster_of_patch.size() != g.patches || g.cluster_share.size() != g.patches)
    throw Error(what, "one cluster and share per patch expected");
  for (std::size_t p = 0; p < g.patches; ++p)
    if (g.cluster_of_patch[p] >= g.clusters ||
        !(g.cluster_share[p] >= 0.0f && g.cluster_share[p] <= 1.0f))
      throw Error(what, "patch " + std::to_string(p) + "'s cluster or share is out of range");
}

// Each near source finite and on a patch that is there.
void check_near_sources(const FinalGather& g, const std::string& what) {
  if (g.near.normal.size() != g.near.size() || g.near.albedo.size() != g.near.size() ||
      g.near.patch.size() != g.near.size())
    throw Error(what, "near sources need a position, normal, albedo and patch each");
  if (g.near.size() > 0 && g.samples == 0)
    throw Error(what, "near sources without the bake's sample count");
  for (std::size_t k = 0; k < g.near.size(); ++k) {
    const glm::vec3 v[3] = {g.near.position[k], g.near.normal[k], g.near.albedo[k]};
    for (const glm::vec3& x : v)
      if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z))
        throw Error(what, "near source " + std::to_string(k) + " is not finite");
    if (g.near.patch[k] >= g.patches)
      throw Error(what, "near source " + std::to_string(k) + " names patch " +
                            std::to_string(g.near.patch[k]) + " of " + std::to_string(g.patches));
  }
}

// Each patch's seen samples in range, their weights summing to 1.
void check_seen_weights(const FinalGather& g, const std::string& what) {
  if (!g.seen_first.empty()) {
    if (g.seen_first.size() != g.patches + 1 || g.seen_first.front() != 0 ||
        g.seen_first.back() != g.seen_sample.size() || g.seen_sample.size() != g.seen_weight.size())
      throw Error(what, "the seen weights' row starts do not match their " +
                            std::to_string(g.seen_sample.size()) + " entries and " +
                            std::to_string(g.patches) + " patches");
    if (g.samples == 0) throw Error(what, "seen weights without the bake's sample count");
    for (std::size_t p = 0; p < g.patches; ++p) {
      // The last start equals the count, but one in between may run past it.
      if (g.seen_first[p + 1] < g.seen_first[p] || g.seen_first[p + 1] > g.seen_sample.size())
        throw Error(what,
                    "the seen weights' row starts decrease or run past their entries at "
                    "patch " +
                        std::to_string(p));
      double total = 0.0;
      for (std::uint32_t k = g.seen_first[p]; k < g.seen_first[p + 1]; ++k) {
        if (g.seen_sample[k] >= g.samples ||
            !(g.seen_weight[k] >= 0.0f && g.seen_weight[k] <= 1.0f))
          throw Error(what, "patch " + std::to_string(p) +
                                "'s seen weights name a sample out of range or a weight "
                                "outside [0, 1]");
        total += g.seen_weight[k];
      }
      if (g.seen_first[p + 1] > g.seen_first[p] && std::abs(total - 1.0) > 1e-3)
        throw Error(what, "patch " + std::to_string(p) + "'s seen weights sum to " +
                              std::to_string(total) + ", not 1");
    }
  }
}

// Each sample's spots among the near sources, their weights summing to 1.
void check_spots(const FinalGather& g, const std::string& what) {
  if (g.near.spot_count != g.spots())
    throw Error(what, "the near sources end in " + std::to_string(g.near.spot_count) +
                          " spots, the spots' row starts name " + std::to_string(g.spots()));
  if (!g.spot_first.empty()) {
    if (g.spot_first.size() != g.samples + 1 || g.spot_first.front() != 0 ||
        g.spot_first.back() != g.spot_weight.size() || g.spot_first.back() > g.near.size())
      throw Error(what, "the spots' row starts do not match their " +
                            std::to_string(g.spot_weight.size()) + " weights, " +
                            std::to_string(g.samples) + " samples and " +
                            std::to_string(g.near.size()) + " near sources");
    for (std::size_t s = 0; s < g.samples; ++s) {
      if (g.spot_first[s + 1] < g.spot_first[s] || g.spot_first[s + 1] > g.spot_weight.size())
        throw Error(what, "the spots' row starts decrease or run past their weights at sample " +
                              std::to_string(s));
      double total = 0.0;
      for (std::uint32_t k = g.spot_first[s]; k < g.spot_first[s + 1]; ++k) {
        if (!(g.spot_weight[k] >= 0.0f && g.spot_weight[k] <= 1.0f))
          throw Error(what, "sample " + std::to_string(s) + " has a spot weight outside [0, 1]");
        total += g.spot_weight[k];
      }
      if (g.spot_first[s + 1] > g.spot_first[s] && std::abs(total - 1.0) > 1e-3)
        throw Error(what, "sample " + std::to_string(s) + "'s spot weights sum to " +
                              std::to_string(total) + ", not 1");
    }
  }
}

// Each point's entries on a source that is there, their weights at most 1.
void check_entries(const FinalGather& g, const std::string& what) {
  for (std::size_t i = 0; i + 1 < g.first.size(); ++i) {
    // The last offset equals the count, but one in between may run past it.
    if (g.first[i + 1] < g.first[i] || g.first[i + 1] > g.source.size())
      throw Error(what,
                  "row offsets decrease or run past the entries at point " + std::to_string(i));
    double total = 0.0;
    for (std::uint64_t k = g.first[i]; k < g.first[i + 1]; ++k) {
      if (g.source[k] >= g.patches + g.clusters + g.samples + g.near.size())
        throw Error(what, "point " + std::to_string(i) + " gathers from source " +
                              std::to_string(g.source[k]) + " of " +
                              std::to_string(g.patches + g.clusters + g.samples + g.near.size()));
      if (!(g.weight[k] >= 0.0f && g.weight[k] <= 1.0f))
        throw Error(what, "point " + std::to_string(i) + " has a weight outside [0, 1]");
      total += g.weight[k];
    }
    if (total > 1.0 + 1e-4)
      throw Error(what, "point " + std::to_string(i) + "'s weights sum to " +
                            std::to_string(total) + " > 1");
  }
}

}  // namespace

void FinalGather::validate(const std::string& what) const {
  check_rows_and_clusters(*this, what);
  check_near_sources(*this, what);
  check_seen_weights(*this, what);
  check_spots(*this, what);
  check_entries(*this, what);
}

}  // namespace bounce
