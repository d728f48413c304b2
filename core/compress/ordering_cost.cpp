#include "compress/ordering_cost.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "base/error.h"

namespace bounce {

double block_spread_cost(const std::uint8_t* image, std::size_t n, std::size_t channels,
                         const Permutation& perm, bool zero_is_hole) {
  if (!perm.empty() && (perm.size() != n || !is_bijection(perm)))
    throw Error("ordering",
                "block_spread_cost: not a permutation of 0.." + std::to_string(n) + "-1");
  const Permutation p = perm.empty() ? identity_permutation(n) : perm;
  const std::size_t blocks = (n + 3) / 4;
  const std::size_t row_bytes = n * channels;
  // One partial sum per block row, added in order afterwards: the result does
  // not depend on the thread count.
  std::vector<double> partial(blocks, 0.0);
#pragma omp parallel for schedule(dynamic, 4) if (n * row_bytes >= (std::size_t{1} << 20))
  for (std::ptrdiff_t bi = 0; bi < static_cast<std::ptrdiff_t>(blocks); ++bi) {
    const std::size_t r0 = static_cast<std::size_t>(bi) * 4, r1 = std::min(n, r0 + 4);
    // The block row reads four source rows only: every gather below hits
    // these 4 * n * channels bytes, which stay in cache.
    const std::uint8_t* rows[4];
    for (std::size_t r = r0; r < r1; ++r) rows[r - r0] = image + p[r] * row_bytes;
    double sum = 0.0;
    int values[16];
    for (std::size_t c0 = 0; c0 < n; c0 += 4) {
      const std::size_t c1 = std::min(n, c0 + 4);
      for (std::size_t ch = 0; ch < channels; ++ch) {
        int count = 0, total = 0;
        for (std::size_t r = 0; r < r1 - r0; ++r)
          for (std::size_t c = c0; c < c1; ++c) {
            const int v = rows[r][p[c] * channels + ch];
            if (v == 0 && zero_is_hole) continue;
            values[count++] = v;
            total += v;
          }
        if (count == 0) continue;
        const double mean = static_cast<double>(total) / count;
        double spread = 0.0;
        for (int k = 0; k < count; ++k) spread += std::abs(values[k] - mean);
        sum += spread;
      }
    }
    partial[static_cast<std::size_t>(bi)] = sum;
  }
  double cost = 0.0;
  for (const double v : partial) cost += v;
  return cost;
}

}  // namespace bounce
