#pragma once
// Temporal radiosity as published: instead of the full
// product T b every frame, each patch p draws S columns q_1..q_S from the
// alias table of row p of T (probability T_pq / sum_q T_pq) and estimates
//   B_new[p] = (sum_q T_pq) / S * sum_s b[q_s],
// an unbiased estimate of (T b)[p] for any b, at O(S) instead of O(N) per
// patch; the frames are blended,
//   B^f = w_f B^(f-1) + (1 - w_f) B_new,   w_f = min(w, f / (f + 1)),
// f counting frames since the last reset: the first frames are a running
// mean (no history to trust yet, and B^0 = 0 would darken them), after that
// the paper's exponential blend with weight w. In the steady state the
// blend's variance is (1 - w) / (1 + w) of one frame's; after a light
// change the old light decays as w^f (the ghosting the bench measures).
//
// One table set per stored channel; a colour uses the tables of its channel
// (channel_of_rgb), colours that share a channel share its samples. Random
// numbers come from dynamic/counter_hash.h: (seed, frame, row, sample, lane)
// -> the same samples on the C++ and OpenCL (temporal_radiosity_cl.h) paths.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "base/progress.h"
#include "dynamic/alias_table.h"

namespace bounce {

struct TemporalSettings {
  int samples_per_patch = 64;   // S
  float history_weight = 0.9f;  // w, in [0, 1)
  std::uint32_t seed = 1;
};

// The blend weight of frame f (0-based since the last reset).
float temporal_blend_weight(float history_weight, std::uint32_t frame);

class TemporalRadiosity {
 public:
  // `matrices`: the stored channels of T (n x n row-major each); the alias
  // tables are built here (O(N^2) per channel). Throws bounce::Error on bad
  // sizes, samples < 1 or a weight outside [0, 1).
  TemporalRadiosity(const std::vector<const float*>& matrices, std::size_t n,
                    const std::array<int, 3>& channel_of_rgb, const TemporalSettings& settings,
                    Progress* progress = nullptr);

  // B_new of frame `frame` for first-hit light b (n entries).
  void estimate(const std::vector<glm::vec3>& b, std::uint32_t frame,
                std::vector<glm::vec3>& b_new) const;
  // The same on raw memory (n entries each; e.g. frame-graph buffers).
  void estimate(const glm::vec3* b, std::uint32_t frame, glm::vec3* b_new) const;

  // One frame: estimate with this object's frame counter, blend into
  // `history` (n entries, updated in place: the blend is element-wise, so one
  // buffer serves as B^(f-1) and B^f), advance the counter.
  void step(const std::vector<glm::vec3>& b, std::vector<glm::vec3>& history);
  void reset() { frame_ = 0; }
  // For callers that run estimate() and temporal_blend() themselves (the
  // frame graph's passes): moves to the next frame.
  void advance_frame() { ++frame_; }
  std::uint32_t frame() const { return frame_; }

  std::size_t size() const { return n_; }
  const TemporalSettings& settings() const { return settings_; }
  const std::vector<AliasTables>& tables() const { return tables_; }
  const std::array<int, 3>& channel_of_rgb() const { return channel_of_rgb_; }
  // Bytes one frame reads: S alias-table slots and S b entries per
  // patch and stored channel, plus the row sums.
  std::size_t bytes_per_frame() const;

 private:
  std::size_t n_;
  std::array<int, 3> channel_of_rgb_;
  TemporalSettings settings_;
  std::vector<AliasTables> tables_;
  std::uint32_t frame_ = 0;
  mutable std::vector<glm::vec3> b_new_;
};

// The blend, element-wise: history = w history + (1 - w) b_new.
void temporal_blend(std::vector<glm::vec3>& history, const std::vector<glm::vec3>& b_new,
                    float weight);
void temporal_blend(glm::vec3* history, const glm::vec3* b_new, std::size_t n, float weight);

}  // namespace bounce
