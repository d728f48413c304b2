#pragma once
// How a bake stores its multi-bounce matrix, and what that costs: decides
// dense or compressed (BakeSettings::codec), chooses the kept fraction from
// the error budget (the light-weighted codec), compresses, and measures every error against the
// exact matrix. Each choice is recorded with its reason.
#include <optional>
#include <string>
#include <vector>

#include "base/diagnostics.h"
#include "base/progress.h"
#include "compress/codec.h"
#include "compress/compression_error.h"
#include "compress/light_rebalance.h"
#include "settings/bake_settings.h"
#include "transport/transport.h"

namespace bounce {

struct KeptFractionTrial {
  double kept_fraction = 0.0;
  double rel_frobenius = 0.0;
  IndirectLightError light;  // what the error budget is measured on
  std::size_t bytes = 0;
  // Patch rows the light error was measured on: a sample of the rows while
  // searching (an estimate), every row for a matrix that could be stored.
  std::size_t rows = 0;
};

struct MatrixStorage {
  std::string codec;  // "dense", "paper" or "ours"
  std::optional<CompressedMatrix> compressed;
  CompressionErrors errors;               // all zero when dense
  std::size_t dense_bytes = 0;            // float32, the stored channels
  std::size_t dense_rgb_bytes = 0;        // float32, three channels: the reference of ratios
  std::size_t stored_bytes = 0;           // what the bake keeps of the matrix
  std::vector<KeptFractionTrial> trials;  // light-weighted codec, error budget
  // The light-weighted codec with an error budget: the budget (relative RMS error of the indirect
  // light on the worst evaluation light), the size the search may spend, and
  // whether the chosen matrix meets the budget.
  std::optional<double> error_budget;
  std::optional<double> size_limit;  // share of dense float32 RGB
  std::size_t size_limit_bytes = 0;
  bool error_budget_met = false;
  // Said plainly: what the search found, and what it did when the budget
  // could not be met within the size limit.
  std::string error_budget_outcome;
  std::vector<TransportDecision> decisions;
  // Compressed, with a stored final gather: the same indirect-light error at
  // the lit mesh's vertices, after the gather (bake/vertex_light_error.h).
  std::optional<IndirectLightError> vertex_indirect;
  // Sum over stored channels of |T~ - T| per entry (patch order); empty when dense.
  std::vector<float> abs_error_sum;
  double seconds = 0.0;

  double ratio_to_dense_rgb() const {
    return stored_bytes > 0
               ? static_cast<double>(dense_rgb_bytes) / static_cast<double>(stored_bytes)
               : 0.0;
  }
};

// Kept fractions tried by the error budget, smallest first. Steps of about
// 1.5x around the few percent where real scenes meet the budget: each step
// up costs 8 bytes per entry kept and channel.
inline constexpr double kKeptFractionLadder[] = {0.0025, 0.005, 0.01, 0.015, 0.02, 0.03, 0.04,
                                                 0.06,   0.08,  0.12, 0.16,  0.24, 0.32};

// The search measures each kept fraction on every kSearchSampleStride-th
// block row of the ordered matrix (at least kSearchSampleMinBlockRows of
// them), then compresses the whole matrix once at the fraction found and
// measures that. A matrix whose sample would be every block row is searched
// on whole compressions.
inline constexpr std::size_t kSearchSampleStride = 8;
inline constexpr std::size_t kSearchSampleMinBlockRows = 128;

// The sampled block rows for an n x n matrix (ascending).
std::vector<std::uint32_t> search_sample_block_rows(std::size_t n);

// `executor`: where the block encoding of every compression tried runs (a
// distributed bake's ranks; compress_matrix); nullptr: in this process.
MatrixStorage store_transport(const TransportResult& transport, const IndirectLightProbe& probe,
                              const BakeSettings& settings, Progress* progress,
                              Diagnostics& diagnostics, CompressionExecutor* executor = nullptr);
// The same from the stored channels alone (n x n each, patch order): the
// bake's compression stage, and the studio's re-compression of a bake folder's
// exact T.npy with another codec or ordering for comparison.
MatrixStorage store_matrices(const std::vector<const float*>& exact, std::size_t n,
                             const IndirectLightProbe& probe, const BakeSettings& settings,
                             Progress* progress, Diagnostics& diagnostics,
                             CompressionExecutor* executor = nullptr);

// The stored channels of `transport` as matrix pointers, and which of them
// stands for R, G and B.
std::vector<const float*> stored_channels(const TransportResult& transport);
std::array<int, 3> channel_of_rgb(const TransportResult& transport);

}  // namespace bounce
