#include "runtime/seen_first_hit.h"

#include <string>

#include "base/error.h"

namespace bounce {

void set_seen_weights(const FinalGather& gather, PatchSet& patches, const std::string& what) {
  patches.member_seen_weight.clear();
  if (gather.seen_first.empty()) return;
  const std::size_t n = patches.size();
  if (gather.patches != n || gather.seen_first.size() != n + 1)
    throw Error(what, "seen weights for " + std::to_string(gather.seen_first.size() - 1) +
                          " patches, the bake has " + std::to_string(n));
  const std::vector<std::uint32_t>& first = gather.seen_first;
  if (first.front() != 0 || first.back() != gather.seen_sample.size() ||
      gather.seen_weight.size() != gather.seen_sample.size())
    throw Error(what, "the seen weights' row starts do not match their " +
                          std::to_string(gather.seen_sample.size()) + " entries");
  for (std::size_t p = 0; p < n; ++p)
    if (first[p + 1] < first[p])
      throw Error(what, "the seen weights' row starts decrease at patch " + std::to_string(p));
  for (const float w : gather.seen_weight)
    if (!(w >= 0.0f && w <= 1.0f)) throw Error(what, "a seen weight is outside [0, 1]");
  std::vector<float> weight(patches.member_samples.size(), 0.0f);
  for (std::size_t p = 0; p < n; ++p)
    for (std::uint32_t k = gather.seen_first[p]; k < gather.seen_first[p + 1]; ++k) {
      // Rows are short (the samples of one patch): a scan finds the member.
      std::uint32_t m = patches.member_first[p];
      while (m < patches.member_first[p + 1] && patches.member_samples[m] != gather.seen_sample[k])
        ++m;
      if (m == patches.member_first[p + 1])
        throw Error(what, "patch " + std::to_string(p) + "'s seen weights name sample " +
                              std::to_string(gather.seen_sample[k]) +
                              ", which is not one of its members");
      weight[m] = gather.seen_weight[k];
    }
  patches.member_seen_weight = std::move(weight);
}

void seen_first_hit(const SampleSet& samples, const PatchSet& patches,
                    std::span<const glm::vec3> irradiance,
                    std::span<const glm::vec3> sample_irradiance, std::span<glm::vec3> first_hit) {
  const std::size_t n = patches.size();
  if (irradiance.size() != n || first_hit.size() != n)
    throw Error("first hit", "one irradiance and one b per patch expected");
  const bool seen = !patches.member_seen_weight.empty();
  if (seen && (patches.member_seen_weight.size() != patches.member_samples.size() ||
               sample_irradiance.size() != samples.samples.size()))
    throw Error("first hit", "seen weights need one weight per member and one E per sample");
#pragma omp parallel for schedule(static, 256)
  for (std::int64_t pi = 0; pi < static_cast<std::int64_t>(n); ++pi) {
    const auto p = static_cast<std::size_t>(pi);
    glm::vec3 b(0.0f);
    float total = 0.0f;
    if (seen)
      for (std::uint32_t m = patches.member_first[p]; m < patches.member_first[p + 1]; ++m) {
        const float w = patches.member_seen_weight[m];
        if (w == 0.0f) continue;
        const std::uint32_t s = patches.member_samples[m];
        b += w * samples.samples[s].albedo * sample_irradiance[s];
        total += w;
      }
    first_hit[p] = total > 0.0f ? b : patches.patches[p].albedo * irradiance[p];
  }
}

}  // namespace bounce
