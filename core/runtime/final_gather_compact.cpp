// Packing a gather's rows into 32-bit entries (a ray count and a source) and
// picking the loop that sums them fastest on this CPU. Kept apart from the
// per-frame product: a bake folder's reader packs a stored gather with this
// alone, without the ray tracer the product lights near sources with.
#include "runtime/final_gather.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "runtime/gather_row_loops.h"

namespace bounce {

namespace {

using gather_loops::PaddedLight;

gather_loops::CompactRows compact_rows_of(const FinalGather& g,
                                          const std::vector<PaddedLight>& light) {
  return {light.data(), g.first.data(), g.compact.data(), g.compact_count_bits,
          static_cast<float>(1.0 / g.compact_rays)};
}

// Which compact loop sums these rows fastest: each runs the whole product
// once to warm its caches, then three times timed, and the fastest time
// counts. Which is fastest depends on the CPU (how it splits wide
// instructions, how many loads it issues a cycle) more than on its feature
// flags, so it is measured on the rows themselves.
//
// Only loops that give the same light compete: the fused ones where this CPU
// has them, else the portable one. (Between the portable and a fused loop a
// timing race would decide the last bits of the light, and two processes
// lighting the same bake could disagree.)
std::string fastest_compact_loop(const FinalGather& g) {
  std::vector<gather_loops::CompactLoop> loops = gather_loops::compact_loops();
  if (std::any_of(loops.begin(), loops.end(), [](const auto& l) { return l.fused; }))
    std::erase_if(loops, [](const auto& l) { return !l.fused; });
  if (loops.size() == 1) return loops.front().name;
  std::vector<PaddedLight> light(g.patches + g.clusters + g.samples + g.near.size(),
                                 PaddedLight{{1.0f, 1.0f, 1.0f, 0.0f}});
  const gather_loops::CompactRows rows = compact_rows_of(g, light);
  std::vector<glm::vec3> out(g.points());
  using Clock = std::chrono::steady_clock;
  std::string best_name;
  double best = std::numeric_limits<double>::infinity();
  for (const gather_loops::CompactLoop& loop : loops)
    for (int run = 0; run < 4; ++run) {
      const auto start = Clock::now();
      gather_loops::sum_compact_rows(loop, rows, g.points(), out.data());
      const double t = std::chrono::duration<double>(Clock::now() - start).count();
      if (run > 0 && t < best) {
        best = t;
        best_name = loop.name;
      }
    }
  return best_name;
}

}  // namespace

void FinalGather::compact_rows() {
  compact.clear();
  compact_loop.clear();
  compact_count_bits = 0;
  compact_rays = 0;
  if (source.empty() || source.size() != weight.size()) return;
  // The rays per point: the build's `rays`, or (rows read from a bake) the
  // one a smallest weight of one ray gives.
  int r = rays;
  if (r <= 0) {
    float smallest = 1.0f;
    for (const float x : weight)
      if (x > 0.0f) smallest = std::min(smallest, x);
    const double guess = std::round(1.0 / static_cast<double>(smallest));
    if (!(guess >= 1.0 && guess <= 65536.0)) return;
    r = static_cast<int>(guess);
  }
  const int bits = std::bit_width(static_cast<unsigned>(r));
  if (bits >= 32) return;
  const std::uint64_t max_source = (std::uint64_t{1} << (32 - bits)) - 1;
  const double per_ray = 1.0 / static_cast<double>(r);
  std::vector<std::uint32_t> c(source.size());
  for (std::size_t k = 0; k < source.size(); ++k) {
    const double count = std::round(static_cast<double>(weight[k]) * r);
    // The weight must be exactly what the build stores for that count.
    if (!(count >= 0.0 && count <= r) || source[k] > max_source ||
        static_cast<float>(per_ray * count) != weight[k])
      return;
    c[k] = source[k] << bits | static_cast<std::uint32_t>(count);
  }
  compact = std::move(c);
  compact_count_bits = bits;
  compact_rays = r;
  compact_loop = fastest_compact_loop(*this);
}

}  // namespace bounce
