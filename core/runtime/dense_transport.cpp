#include "runtime/dense_transport.h"

#include <cblas.h>

#include <shared_mutex>
#include <string>

#include "base/error.h"
#include "transport/blas_int.h"
#include "transport/blas_kernels.h"

namespace bounce {

// b and indirect are read and written in place as strided float vectors.
static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "glm::vec3 must be three packed floats");

void dense_indirect(const std::vector<const float*>& matrices, std::size_t n,
                    const std::array<int, 3>& channel_of_rgb, const std::vector<glm::vec3>& b,
                    std::vector<glm::vec3>& indirect) {
  if (b.size() == n && indirect.size() != n) indirect.resize(n);
  dense_indirect(matrices, n, channel_of_rgb, std::span<const glm::vec3>(b),
                 std::span<glm::vec3>(indirect));
}

void dense_indirect(const std::vector<const float*>& matrices, std::size_t n,
                    const std::array<int, 3>& channel_of_rgb, std::span<const glm::vec3> b,
                    std::span<glm::vec3> indirect) {
  if (b.size() != n)
    throw Error("dense transport", "b has " + std::to_string(b.size()) + " entries for " +
                                       std::to_string(n) + " patches");
  if (matrices.empty()) throw Error("dense transport", "no matrix given");
  std::array<int, 3> channel{};
  for (std::size_t k = 0; k < 3; ++k) {
    channel[k] = matrices.size() == 1 ? 0 : channel_of_rgb[k];
    if (channel[k] < 0 || static_cast<std::size_t>(channel[k]) >= matrices.size())
      throw Error("dense transport", "channel_of_rgb maps colour " + std::to_string(k) +
                                         " to stored channel " + std::to_string(channel[k]) +
                                         " of " + std::to_string(matrices.size()));
  }
  if (indirect.size() != n)
    throw Error("dense transport", "the output has " + std::to_string(indirect.size()) +
                                       " entries for " + std::to_string(n) + " patches");
  if (n == 0) return;
  const int dim = blas_dim(n, "cblas_sgemv");
  const float* x = &b[0].x;
  float* y = &indirect[0].x;
  // The studio runs this on its view jobs and its preview while a bake may
  // restart OpenBLAS's threads (transport/blas_kernels.h).
  const std::shared_lock lock(blas_threads_mutex());
  // One sgemv per colour even when colours share a matrix: an n x 3 sgemm
  // would read it once, but OpenBLAS's took 1.7-2.8x as long as three sgemv
  // at n = 4096 here (its packing does not pay for 3 columns).
  for (std::size_t k = 0; k < 3; ++k)
    cblas_sgemv(CblasRowMajor, CblasNoTrans, dim, dim, 1.0f,
                matrices[static_cast<std::size_t>(channel[k])], dim, x + k, 3, 0.0f, y + k, 3);
}

}  // namespace bounce
