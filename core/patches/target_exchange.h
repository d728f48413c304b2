#pragma once
// The clustering's feature vectors: for each sample, the bounded exchange
// (base/form_factor_kernel.h) summed over each target's samples. The sums
// cover every pair of samples, so they are the clustering's largest cost;
// they are computed for kExchangeLanes source samples at once, one per SIMD
// lane, each lane adding its terms in the same order as a scalar loop over
// bounded_exchange, so that the sums are the same to the last bit.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "base/form_factor_kernel.h"

namespace bounce {

inline constexpr std::size_t kExchangeLanes = 8;

// Target points, grouped by target, one array per coordinate.
struct TargetPoints {
  std::vector<float> x, y, z, nx, ny, nz, area;
  std::vector<std::uint32_t> first;  // target t holds points [first[t], first[t + 1])

  std::size_t targets() const { return first.empty() ? 0 : first.size() - 1; }
  void add_target(const std::vector<SurfacePoint>& points);
};

// sums[t * kExchangeLanes + l] = sum over target t's points p, in their order,
// of bounded_exchange(sources[l], p), for l < count (at most kExchangeLanes);
// lanes from count on hold 0. `sums` holds targets() * kExchangeLanes floats.
void exchange_with_targets(const SurfacePoint* sources, std::size_t count,
                           const TargetPoints& targets, float* sums);

}  // namespace bounce
