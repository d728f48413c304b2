#include "patches/target_exchange.h"

#include <algorithm>
#include <cstring>
#include <numbers>

namespace bounce {

namespace {

// Eight floats: two SSE registers on plain x86-64, one AVX register in the
// AVX2 clone. Each lane's arithmetic is IEEE single precision as in the
// scalar kernel, and no operation is fused: neither x86-64's baseline nor the
// clone's "avx2" target enables FMA, so the compiler cannot contract.
using F8 = float __attribute__((vector_size(32)));
using I8 = int __attribute__((vector_size(32)));

inline bool any_lane(I8 mask) {
  std::uint64_t words[4];
  std::memcpy(words, &mask, sizeof words);
  return (words[0] | words[1] | words[2] | words[3]) != 0;
}

struct Sources {
  F8 x, y, z, nx, ny, nz, area;
};

Sources load_sources(const SurfacePoint* sources, std::size_t count) {
  Sources s{};
  for (std::size_t l = 0; l < count; ++l) {
    s.x[l] = sources[l].position.x;
    s.y[l] = sources[l].position.y;
    s.z[l] = sources[l].position.z;
    s.nx[l] = sources[l].normal.x;
    s.ny[l] = sources[l].normal.y;
    s.nz[l] = sources[l].normal.z;
    s.area[l] = sources[l].area;
  }
  return s;
}

}  // namespace

void TargetPoints::add_target(const std::vector<SurfacePoint>& points) {
  if (first.empty()) first.push_back(0);
  for (const SurfacePoint& p : points) {
    x.push_back(p.position.x);
    y.push_back(p.position.y);
    z.push_back(p.position.z);
    nx.push_back(p.normal.x);
    ny.push_back(p.normal.y);
    nz.push_back(p.normal.z);
    area.push_back(p.area);
  }
  first.push_back(static_cast<std::uint32_t>(x.size()));
}

// Cloned for AVX2 (chosen at load by the CPU's features): the same lanes in
// one register instead of two.
__attribute__((target_clones("avx2", "default"))) void exchange_with_targets(
    const SurfacePoint* sources, std::size_t count, const TargetPoints& targets, float* sums) {
  count = std::min(count, kExchangeLanes);
  const Sources a = load_sources(sources, count);
  const F8 zero{};
  const F8 pi = zero + std::numbers::pi_v<float>, half = zero + 0.5f;
  // Lanes without a source have area 0 and a zero normal: fa = 0 masks them.
  for (std::size_t t = 0; t < targets.targets(); ++t) {
    F8 sum = zero;
    for (std::uint32_t j = targets.first[t]; j < targets.first[t + 1]; ++j) {
      // The scalar kernel's operations in its order: d = b - a, dot products
      // as (x + y) + z, then a_A b_A (fa fb / r2) / (pi r2 + (a_A + b_A) / 2).
      const F8 dx = targets.x[j] - a.x, dy = targets.y[j] - a.y, dz = targets.z[j] - a.z;
      const F8 r2 = dx * dx + dy * dy + dz * dz;
      const F8 fa = a.nx * dx + a.ny * dy + a.nz * dz;
      const F8 fb = -(targets.nx[j] * dx + targets.ny[j] * dy + targets.nz[j] * dz);
      const I8 facing = (fa > zero) & (fb > zero) & (r2 > zero);
      // Sources next to each other mostly face a point alike: skip the
      // divisions when none of them does.
      if (!any_lane(facing)) continue;
      const F8 b_area = zero + targets.area[j];
      const F8 g = a.area * b_area * (fa * fb / r2) / (pi * r2 + half * (a.area + b_area));
      sum += facing ? g : zero;
    }
    std::copy_n(reinterpret_cast<const float*>(&sum), kExchangeLanes, sums + t * kExchangeLanes);
  }
}

}  // namespace bounce
