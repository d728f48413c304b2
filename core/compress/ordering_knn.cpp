#include "compress/ordering_knn.h"

#include <cblas.h>

#include <algorithm>
#include <limits>
#include <string>
#include <utility>

#include "base/error.h"

namespace bounce {

NeighbourLists nearest_neighbours(const float* points, std::size_t n, std::size_t dims,
                                  std::size_t k) {
  NeighbourLists out;
  out.k = n > 0 ? std::min(k, n - 1) : 0;
  if (out.k == 0) return out;
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max()) ||
      dims > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw Error("ordering", "nearest_neighbours: " + std::to_string(n) + " points is too many");
  const std::size_t kk = out.k;
  out.index.resize(n * kk);
  // Candidates kept per point from the sgemm form before exact re-measuring:
  // a few more than k absorb its rounding.
  const std::size_t keep = std::min(n - 1, kk + 4);
  std::vector<float> norm(n);
  for (std::size_t i = 0; i < n; ++i) {
    float s = 0.0f;
    for (std::size_t t = 0; t < dims; ++t) s += points[i * dims + t] * points[i * dims + t];
    norm[i] = s;
  }
  const std::size_t tile = std::clamp<std::size_t>((std::size_t{1} << 22) / n, 16, 1024);
  std::vector<float> dot(tile * n);
  const int ni = static_cast<int>(n), di = static_cast<int>(dims);
  for (std::size_t i0 = 0; i0 < n; i0 += tile) {
    const std::size_t rows = std::min(tile, n - i0);
    cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasTrans, static_cast<int>(rows), ni, di, 1.0f,
                points + i0 * dims, di, points, di, 0.0f, dot.data(), ni);
#pragma omp parallel if (rows * n >= (std::size_t{1} << 16))
    {
      std::vector<std::pair<float, std::uint32_t>> best;
      best.reserve(keep + 1);
#pragma omp for schedule(static)
      for (std::ptrdiff_t r = 0; r < static_cast<std::ptrdiff_t>(rows); ++r) {
        const std::size_t i = i0 + static_cast<std::size_t>(r);
        const float* d = dot.data() + static_cast<std::size_t>(r) * n;
        best.clear();
        float worst = std::numeric_limits<float>::infinity();
        for (std::size_t j = 0; j < n; ++j) {
          if (j == i) continue;
          const float approx = norm[i] + norm[j] - 2.0f * d[j];
          if (best.size() == keep && approx >= worst) continue;
          // Sorted insertion into a list of at most keep + 1 entries.
          auto pos = std::upper_bound(best.begin(), best.end(),
                                      std::make_pair(approx, static_cast<std::uint32_t>(j)));
          best.insert(pos, {approx, static_cast<std::uint32_t>(j)});
          if (best.size() > keep) best.pop_back();
          if (best.size() == keep) worst = best.back().first;
        }
        for (auto& [dist, j] : best)
          dist = squared_distance(points + i * dims, points + std::size_t{j} * dims, dims);
        std::sort(best.begin(), best.end());
        for (std::size_t t = 0; t < kk; ++t) out.index[i * kk + t] = best[t].second;
      }
    }
  }
  return out;
}

}  // namespace bounce
