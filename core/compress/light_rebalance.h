#pragma once
// Compression measured against the exact matrix, and for ours with an
// EntryImportance, once more with the lights rebalanced. The importance
// averages the evaluation lights, while the error budget holds the worst of
// them: a second compression counts each light by its share of the first's
// squared light error, and the one whose worst light is better is kept. The
// second compression is tried only when the first's worst light is more than
// kRebalanceSpread times its mean: rebalancing moves error from the worst
// light to the others, and has never brought the worst below the first's
// mean (Cornell box, Sponza), so a narrower spread leaves it too little to
// gain for a whole compression.
#include <vector>

#include "base/progress.h"
#include "compress/codec.h"
#include "compress/compression_error.h"

namespace bounce {

inline constexpr double kRebalanceSpread = 1.25;

struct MeasuredCompression {
  CompressedMatrix compressed;
  CompressionErrors errors;
};

// The worst evaluation light's relative RMS error: what the budget bounds.
inline double budgeted_light_error(const IndirectLightError& e) { return e.rel_rms_max; }

// Whether the worst light stands out from the mean enough for rebalancing
// the lights to be tried.
inline bool lights_unbalanced(const IndirectLightError& e) {
  return budgeted_light_error(e) > kRebalanceSpread * e.rel_rms_mean;
}

// Compresses `exact` (stored channels, n x n each) with `codec` and measures
// it against `probe`; `abs_error_sum` as measure_compression. With
// codec.importance (ours), also tries the rebalanced lights (see above).
MeasuredCompression compress_for_light(const std::vector<const float*>& exact, std::size_t n,
                                       const CodecSettings& codec, const IndirectLightProbe& probe,
                                       std::vector<float>* abs_error_sum, Progress* progress,
                                       CompressionExecutor* executor = nullptr);

// compress_for_light's second half: `first` (compressed with `codec` and
// measured; `abs_error_sum` holding its map, if wanted), or the rebalanced
// compression when that one's worst light is better. A compression whose
// rebalancing was already tried is returned as it is.
MeasuredCompression rebalance_for_light(MeasuredCompression first,
                                        const std::vector<const float*>& exact, std::size_t n,
                                        const CodecSettings& codec, const IndirectLightProbe& probe,
                                        std::vector<float>* abs_error_sum, Progress* progress,
                                        CompressionExecutor* executor = nullptr);

}  // namespace bounce
