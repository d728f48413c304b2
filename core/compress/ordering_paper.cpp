#include "compress/ordering_paper.h"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "base/error.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define BOUNCE_ORDERING_X86 1
#endif

namespace bounce {
namespace {

// Summing stops between chunks of this many bytes once the partial sum
// exceeds the bound: small enough to skip most of a far row, large enough
// that the check costs nothing.
constexpr std::size_t kChunk = 1024;
constexpr std::uint64_t kNoBound = std::numeric_limits<std::uint64_t>::max();

std::uint64_t l1_tail(const std::uint8_t* a, const std::uint8_t* b, std::size_t begin,
                      std::size_t end) {
  std::uint64_t s = 0;
  for (std::size_t k = begin; k < end; ++k) s += static_cast<std::uint64_t>(std::abs(a[k] - b[k]));
  return s;
}

#if BOUNCE_ORDERING_X86
// Returns the exact distance, or some partial sum > bound (the caller then
// only needs to know that the row lost).
__attribute__((target("avx2"))) std::uint64_t l1_bounded_avx2(const std::uint8_t* a,
                                                              const std::uint8_t* b,
                                                              std::size_t length,
                                                              std::uint64_t bound) {
  std::uint64_t total = 0;
  std::size_t k = 0;
  const std::size_t simd_end = length & ~std::size_t{63};
  while (k < simd_end) {
    const std::size_t chunk_end = std::min(simd_end, k + kChunk);
    __m256i acc0 = _mm256_setzero_si256(), acc1 = _mm256_setzero_si256();
    for (; k < chunk_end; k += 64) {
      const __m256i a0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(a + k));
      const __m256i b0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(b + k));
      const __m256i a1 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(a + k + 32));
      const __m256i b1 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(b + k + 32));
      acc0 = _mm256_add_epi64(acc0, _mm256_sad_epu8(a0, b0));
      acc1 = _mm256_add_epi64(acc1, _mm256_sad_epu8(a1, b1));
    }
    const __m256i acc = _mm256_add_epi64(acc0, acc1);
    const __m128i s = _mm_add_epi64(_mm256_castsi256_si128(acc), _mm256_extracti128_si256(acc, 1));
    total += static_cast<std::uint64_t>(_mm_cvtsi128_si64(s)) +
             static_cast<std::uint64_t>(_mm_extract_epi64(s, 1));
    if (total > bound) return total;
  }
  return total + l1_tail(a, b, k, length);
}

// SSE2 is part of x86-64, so this needs no dispatch.
std::uint64_t l1_bounded_sse2(const std::uint8_t* a, const std::uint8_t* b, std::size_t length,
                              std::uint64_t bound) {
  std::uint64_t total = 0;
  std::size_t k = 0;
  const std::size_t simd_end = length & ~std::size_t{15};
  while (k < simd_end) {
    const std::size_t chunk_end = std::min(simd_end, k + kChunk);
    __m128i acc = _mm_setzero_si128();
    for (; k < chunk_end; k += 16)
      acc = _mm_add_epi64(acc,
                          _mm_sad_epu8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(a + k)),
                                       _mm_loadu_si128(reinterpret_cast<const __m128i*>(b + k))));
    total += static_cast<std::uint64_t>(_mm_cvtsi128_si64(acc)) +
             static_cast<std::uint64_t>(_mm_cvtsi128_si64(_mm_unpackhi_epi64(acc, acc)));
    if (total > bound) return total;
  }
  return total + l1_tail(a, b, k, length);
}

using L1Function = std::uint64_t (*)(const std::uint8_t*, const std::uint8_t*, std::size_t,
                                     std::uint64_t);
L1Function select_l1() {
  // The build targets plain x86-64; AVX2 doubles the bytes per instruction
  // where the CPU has it.
  return __builtin_cpu_supports("avx2") ? l1_bounded_avx2 : l1_bounded_sse2;
}
#else
std::uint64_t l1_bounded_plain(const std::uint8_t* a, const std::uint8_t* b, std::size_t length,
                               std::uint64_t bound) {
  std::uint64_t total = 0;
  for (std::size_t k = 0; k < length; k += kChunk) {
    total += l1_tail(a, b, k, std::min(length, k + kChunk));
    if (total > bound) return total;
  }
  return total;
}
using L1Function = std::uint64_t (*)(const std::uint8_t*, const std::uint8_t*, std::size_t,
                                     std::uint64_t);
L1Function select_l1() { return l1_bounded_plain; }
#endif

std::uint64_t l1_bounded(const std::uint8_t* a, const std::uint8_t* b, std::size_t length,
                         std::uint64_t bound) {
  static const L1Function f = select_l1();
  return f(a, b, length, bound);
}

}  // namespace

std::uint64_t l1_distance(const std::uint8_t* a, const std::uint8_t* b, std::size_t length) {
  return l1_bounded(a, b, length, kNoBound);
}

Permutation greedy_l1_tour(const std::uint8_t* rows, std::size_t count, std::size_t row_bytes) {
  Permutation order;
  if (count == 0) return order;
  order.reserve(count);
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  // Unvisited rows in a compact list (swap-remove) so each step scans only
  // them; `slot` finds a row's place in the list.
  std::vector<std::uint32_t> left(count - 1), slot(count);
  std::vector<char> visited(count, 0);
  for (std::size_t k = 1; k < count; ++k) {
    left[k - 1] = static_cast<std::uint32_t>(k);
    slot[k] = static_cast<std::uint32_t>(k - 1);
  }
  std::uint32_t current = 0, runner_up = kNone;
  visited[0] = 1;
  order.push_back(current);
  auto row = [&](std::uint32_t r) { return rows + static_cast<std::size_t>(r) * row_bytes; };
  // (distance, index) pairs compare lexicographically: the smaller index
  // wins a tie, as the published rule needs.
  struct Candidate {
    std::uint64_t d = kNoBound;
    std::uint32_t i = kNone;
    bool operator<(const Candidate& o) const { return d < o.d || (d == o.d && i < o.i); }
  };
  while (!left.empty()) {
    const std::uint8_t* cur = row(current);
    // Early abandoning works as well as its first bound. Rows near the
    // current one are likely: the runner-up of the previous step (near the
    // previous row, hence near this one) and the next row index (patch order
    // is partly coherent). Their exact distances bound the search from the
    // start; the result is the same as without them.
    Candidate seed;
    for (const std::uint32_t h : {runner_up, current + 1 < count ? current + 1 : kNone})
      if (h != kNone && !visited[h])
        seed = std::min(seed, Candidate{l1_distance(cur, row(h), row_bytes), h});
    Candidate best = seed, second;
    // Threads only for steps that may read 32 MB or more (with early
    // abandoning they read ~10% of it, a millisecond): one fork/join per step
    // costs microseconds on an idle machine but milliseconds when the cores
    // are shared, which made 2 threads 10x slower than 1 at n = 4096 here.
#pragma omp parallel if (left.size() * row_bytes >= (std::size_t{1} << 25))
    {
      // Each thread abandons rows against its own best so far (never above
      // the global best, so no row that could win or tie is abandoned).
      Candidate mine = seed, my_second;
#pragma omp for schedule(dynamic, 16) nowait
      for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(left.size()); ++k) {
        const std::uint32_t r = left[static_cast<std::size_t>(k)];
        if (r == seed.i) continue;
        const Candidate c{l1_bounded(cur, row(r), row_bytes, mine.d), r};
        if (c < mine) {
          my_second = mine;
          mine = c;
        } else if (c.d <= mine.d && c < my_second) {
          my_second = c;  // an exact distance too (not abandoned)
        }
      }
#pragma omp critical(bounce_ordering_paper_min)
      {
        for (const Candidate& c : {mine, my_second}) {
          if (c.i == kNone || c.i == best.i || c.i == second.i) continue;
          if (c < best) {
            second = best;
            best = c;
          } else if (c < second) {
            second = c;
          }
        }
      }
    }
    const std::uint32_t s = slot[best.i];
    left[s] = left.back();
    slot[left[s]] = s;
    left.pop_back();
    visited[best.i] = 1;
    order.push_back(best.i);
    current = best.i;
    runner_up = second.i;
  }
  return order;
}

Permutation paper_ordering(const std::uint8_t* image, std::size_t n, std::size_t channels,
                           int passes) {
  if (passes != 1 && passes != 2)
    throw Error("ordering", "paper_ordering: passes must be 1 or 2, got " + std::to_string(passes));
  if (channels == 0) throw Error("ordering", "paper_ordering: no channels");
  const std::size_t row_bytes = n * channels;
  // The L1 distance between two rows does not depend on the column order, so
  // pass 1 reads the rows of the original image directly.
  const Permutation p1 = greedy_l1_tour(image, n, row_bytes);
  if (passes == 1) return p1;

  // Pass 2 walks the columns of image1 = apply_symmetric(image, p1). Column i
  // of image1 becomes row i of `columns`, its entries in image1's row order
  // (image1[r][i] = image[p1[r]][p1[i]]). Tiles keep both the reads and the
  // writes in cache.
  std::vector<std::uint8_t> columns(n * row_bytes);
  constexpr std::size_t kTile = 64;
  const std::size_t tiles = (n + kTile - 1) / kTile;
#pragma omp parallel for schedule(dynamic, 1) if (n * row_bytes >= (std::size_t{1} << 20))
  for (std::ptrdiff_t t = 0; t < static_cast<std::ptrdiff_t>(tiles * tiles); ++t) {
    const std::size_t i0 = static_cast<std::size_t>(t) / tiles * kTile;
    const std::size_t r0 = static_cast<std::size_t>(t) % tiles * kTile;
    for (std::size_t r = r0; r < std::min(n, r0 + kTile); ++r) {
      const std::uint8_t* src = image + static_cast<std::size_t>(p1[r]) * row_bytes;
      for (std::size_t i = i0; i < std::min(n, i0 + kTile); ++i)
        for (std::size_t c = 0; c < channels; ++c)
          columns[i * row_bytes + r * channels + c] = src[p1[i] * channels + c];
    }
  }
  const Permutation p2 = greedy_l1_tour(columns.data(), n, row_bytes);
  return compose(p1, p2);
}

}  // namespace bounce
