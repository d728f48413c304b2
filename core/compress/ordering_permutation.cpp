#include "compress/ordering_permutation.h"

#include <cstring>
#include <numeric>
#include <string>

#include "base/error.h"

namespace bounce {

Permutation identity_permutation(std::size_t n) {
  Permutation p(n);
  std::iota(p.begin(), p.end(), 0u);
  return p;
}

bool is_bijection(const Permutation& p) {
  std::vector<bool> seen(p.size(), false);
  for (const std::uint32_t v : p) {
    if (v >= p.size() || seen[v]) return false;
    seen[v] = true;
  }
  return true;
}

Permutation inverse(const Permutation& p) {
  Permutation q(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) q[p[i]] = static_cast<std::uint32_t>(i);
  return q;
}

Permutation compose(const Permutation& first, const Permutation& second) {
  if (first.size() != second.size())
    throw Error("ordering", "compose: permutations of different sizes (" +
                                std::to_string(first.size()) + " and " +
                                std::to_string(second.size()) + ")");
  Permutation r(second.size());
  for (std::size_t i = 0; i < second.size(); ++i) r[i] = first[second[i]];
  return r;
}

std::vector<std::uint8_t> apply_symmetric(const std::uint8_t* image, std::size_t n,
                                          std::size_t channels, const Permutation& p) {
  if (p.size() != n || !is_bijection(p))
    throw Error("ordering", "apply_symmetric: not a permutation of 0.." + std::to_string(n) + "-1");
  const std::size_t row_bytes = n * channels;
  std::vector<std::uint8_t> out(n * row_bytes);
  // One output row gathers from one input row: the gather stays inside a
  // single source row (n * channels bytes, cache resident) however scattered p
  // is, so the cost is one streaming pass over the image. Small images stay
  // on one thread: a fork/join costs more than they do on a busy machine.
#pragma omp parallel for schedule(static) if (n * row_bytes >= (std::size_t{1} << 20))
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(n); ++i) {
    const std::uint8_t* src =
        image + static_cast<std::size_t>(p[static_cast<std::size_t>(i)]) * row_bytes;
    std::uint8_t* dst = out.data() + static_cast<std::size_t>(i) * row_bytes;
    if (channels == 3) {
      for (std::size_t j = 0; j < n; ++j) {
        const std::uint8_t* s = src + static_cast<std::size_t>(p[j]) * 3;
        dst[3 * j] = s[0];
        dst[3 * j + 1] = s[1];
        dst[3 * j + 2] = s[2];
      }
    } else {
      for (std::size_t j = 0; j < n; ++j)
        std::memcpy(dst + j * channels, src + static_cast<std::size_t>(p[j]) * channels, channels);
    }
  }
  return out;
}

std::vector<std::uint8_t> unapply_symmetric(const std::uint8_t* permuted, std::size_t n,
                                            std::size_t channels, const Permutation& p) {
  // permuted[i][j] = x[p[i]][p[j]]  =>  x[a][b] = permuted[q[a]][q[b]], q = p^-1.
  if (p.size() != n || !is_bijection(p))
    throw Error("ordering",
                "unapply_symmetric: not a permutation of 0.." + std::to_string(n) + "-1");
  return apply_symmetric(permuted, n, channels, inverse(p));
}

}  // namespace bounce
