#include "dynamic/temporal_radiosity.h"

#include <algorithm>
#include <limits>
#include <string>

#include "base/error.h"
#include "dynamic/counter_hash.h"

namespace bounce {

float temporal_blend_weight(float history_weight, std::uint32_t frame) {
  const float running_mean = static_cast<float>(frame) / (static_cast<float>(frame) + 1.0f);
  return std::min(history_weight, running_mean);
}

TemporalRadiosity::TemporalRadiosity(const std::vector<const float*>& matrices, std::size_t n,
                                     const std::array<int, 3>& channel_of_rgb,
                                     const TemporalSettings& settings, Progress* progress)
    : n_(n), channel_of_rgb_(channel_of_rgb), settings_(settings) {
  if (matrices.empty() || matrices.size() > 3)
    throw Error("temporal radiosity", std::to_string(matrices.size()) + " stored channels");
  if (n > std::numeric_limits<std::uint32_t>::max())
    throw Error("temporal radiosity", "too many patches for 32-bit indices");
  for (int c : channel_of_rgb_)
    if (c < 0 || static_cast<std::size_t>(c) >= matrices.size())
      throw Error("temporal radiosity", "colour mapped to missing channel " + std::to_string(c));
  if (settings_.samples_per_patch < 1)
    throw Error("temporal radiosity", "samples per patch must be at least 1");
  if (!(settings_.history_weight >= 0.0f && settings_.history_weight < 1.0f))
    throw Error("temporal radiosity", "history weight must be in [0, 1)");
  for (const float* m : matrices) tables_.push_back(build_alias_tables(m, n, n, progress));
}

void TemporalRadiosity::estimate(const std::vector<glm::vec3>& b, std::uint32_t frame,
                                 std::vector<glm::vec3>& b_new) const {
  if (b.size() != n_)
    throw Error("temporal radiosity", "b has " + std::to_string(b.size()) + " entries for " +
                                          std::to_string(n_) + " patches");
  b_new.resize(n_);
  estimate(b.data(), frame, b_new.data());
}

void TemporalRadiosity::estimate(const glm::vec3* b, std::uint32_t frame, glm::vec3* b_new) const {
  std::fill(b_new, b_new + n_, glm::vec3(0.0f));
  const auto n32 = static_cast<std::uint32_t>(n_);
  const auto samples = static_cast<std::uint32_t>(settings_.samples_per_patch);
  const auto rows = static_cast<std::ptrdiff_t>(n_);
  for (std::size_t c = 0; c < tables_.size(); ++c) {
    const AliasTables& t = tables_[c];
    glm::vec3 mask(0.0f);
    for (int k = 0; k < 3; ++k)
      if (static_cast<std::size_t>(channel_of_rgb_[static_cast<std::size_t>(k)]) == c)
        mask[k] = 1.0f;
    if (mask == glm::vec3(0.0f)) continue;
    const auto lane = static_cast<std::uint32_t>(2 * c);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
      const auto p = static_cast<std::uint32_t>(r);
      const AliasEntry* table = t.entries.data() + static_cast<std::size_t>(p) * n_;
      // Summed in sample order in float, as the kernel does.
      glm::vec3 acc(0.0f);
      const std::uint32_t index_stream = row_stream(settings_.seed, frame, p, lane);
      const std::uint32_t coin_stream = row_stream(settings_.seed, frame, p, lane + 1);
      for (std::uint32_t s = 0; s < samples; ++s) {
        // = sample_hash(seed, frame, p, s, lane) and (..., lane + 1).
        const std::uint32_t i = hash_to_index(hash32(index_stream ^ s), n32);
        const float u = hash_to_unit(hash32(coin_stream ^ s));
        acc += b[alias_sample(table, i, u)];
      }
      const float scale = t.row_sum[p] / static_cast<float>(samples);
      b_new[p] += mask * (acc * scale);
    }
  }
}

void temporal_blend(std::vector<glm::vec3>& history, const std::vector<glm::vec3>& b_new,
                    float weight) {
  if (history.size() != b_new.size())
    throw Error("temporal radiosity", "history and estimate differ in size");
  temporal_blend(history.data(), b_new.data(), history.size(), weight);
}

void temporal_blend(glm::vec3* history, const glm::vec3* b_new, std::size_t n, float weight) {
  for (std::size_t p = 0; p < n; ++p) history[p] = weight * history[p] + (1.0f - weight) * b_new[p];
}

void TemporalRadiosity::step(const std::vector<glm::vec3>& b, std::vector<glm::vec3>& history) {
  estimate(b, frame_, b_new_);
  if (history.size() != n_) history.assign(n_, glm::vec3(0.0f));
  temporal_blend(history, b_new_, temporal_blend_weight(settings_.history_weight, frame_));
  ++frame_;
}

std::size_t TemporalRadiosity::bytes_per_frame() const {
  const std::size_t per_sample = sizeof(AliasEntry) + sizeof(glm::vec3);
  return tables_.size() * n_ *
         (static_cast<std::size_t>(settings_.samples_per_patch) * per_sample + sizeof(float));
}

}  // namespace bounce
