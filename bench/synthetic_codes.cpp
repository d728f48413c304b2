#include "synthetic_codes.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numeric>
#include <random>
#include <thread>

#include "base/error.h"
#include "base/random.h"

namespace bounce {

namespace {

struct Point {
  float x, y, z;
};

// Patch i of the structured order: wall 3i/n, serpentine over a g x g grid.
std::vector<Point> structured_points(std::size_t n, std::uint64_t seed) {
  std::vector<Point> p(n);
  for (std::size_t wall = 0; wall < 3; ++wall) {
    const std::size_t begin = wall * n / 3, end = (wall + 1) * n / 3, m = end - begin;
    const auto g = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(m))));
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t row = k / g, col = row % 2 == 0 ? k % g : g - 1 - k % g;
      Rng jitter(seed, begin + k);
      const float a = (static_cast<float>(col) + jitter.uniform()) / static_cast<float>(g);
      const float b = (static_cast<float>(row) + jitter.uniform()) / static_cast<float>(g);
      p[begin + k] = wall == 0   ? Point{a, 0.0f, b}   // floor
                     : wall == 1 ? Point{a, b, 0.0f}   // back
                                 : Point{0.0f, a, b};  // left
    }
  }
  return p;
}

// ln v_ij of the kernel with its noise; one stream per row keeps it
// independent of the thread count.
struct Kernel {
  const std::vector<Point>& points;
  float ln_v(const Point& a, const Point& b, Rng& noise) const {
    const float dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
    // Sum of four uniforms: mean 2, standard deviation 1/sqrt(3).
    const float g = noise.uniform() + noise.uniform() + noise.uniform() + noise.uniform() - 2.0f;
    return -std::sqrt(dx * dx + dy * dy + dz * dz) / 0.2f + 0.05f * 1.7320508f * g;
  }
};

// Runs body(row) for every row on every hardware thread, rows dealt out in
// chunks (rows cost the same; chunks keep the counter cheap).
template <class Body>
void parallel_rows(std::size_t rows, Body body) {
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::atomic<std::size_t> next{0};
  constexpr std::size_t kChunk = 16;
  auto worker = [&]() {
    for (std::size_t start; (start = next.fetch_add(kChunk)) < rows;)
      for (std::size_t i = start; i < std::min(rows, start + kChunk); ++i) body(i);
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}

}  // namespace

SyntheticCodes synthetic_codes(std::size_t n, std::size_t channels, double kept_fraction,
                               std::uint64_t seed) {
  if (n < 4) throw Error("--n", "must be at least 4, got " + std::to_string(n));
  if (channels < 1 || channels > 4)
    throw Error("--channels", "must be between 1 and 4, got " + std::to_string(channels));
  const auto start = std::chrono::steady_clock::now();
  SyntheticCodes s;
  s.n = n;
  s.channels = channels;
  const std::vector<Point> structured = structured_points(n, seed);

  // The shuffle: patch i of the image is patch shuffle[i] of the structured
  // order; restoring it takes the inverse.
  Permutation shuffle = identity_permutation(n);
  std::mt19937_64 rng(seed);
  std::shuffle(shuffle.begin(), shuffle.end(), rng);
  s.structure = inverse(shuffle);
  std::vector<Point> points(n);
  for (std::size_t i = 0; i < n; ++i) points[i] = structured[shuffle[i]];
  const Kernel kernel{points};

  // Hole threshold: the (1 - kept) quantile of ln v on channel 0, estimated
  // on up to 512 rows (the kernel is the same everywhere up to noise).
  const std::size_t row_step = std::max<std::size_t>(1, n / 512);
  std::vector<float> sample;
  for (std::size_t i = 0; i < n; i += row_step) {
    Rng noise(seed, i);
    for (std::size_t j = 0; j < n; ++j)
      sample.push_back(i == j ? 0.0f : kernel.ln_v(points[i], points[j], noise));
  }
  const auto q = static_cast<std::size_t>(
      std::clamp((1.0 - kept_fraction) * static_cast<double>(sample.size()), 0.0,
                 static_cast<double>(sample.size() - 1)));
  std::nth_element(sample.begin(), sample.begin() + static_cast<std::ptrdiff_t>(q), sample.end());
  const float threshold = kept_fraction > 0.0 ? sample[q] : 1e30f;
  // ln vmax of the quantised remainder: the threshold (code 255 just below
  // it), or the diagonal's 0 when nothing is kept.
  const float ln_vmax = std::min(threshold, 0.0f);
  float shift[4];
  for (std::size_t c = 0; c < 4; ++c) shift[c] = std::log(1.0f - 0.1f * static_cast<float>(c));

  s.image.assign(n * n * channels, 0);
  std::vector<std::size_t> holes_per_row(n, 0);
  parallel_rows(n, [&](std::size_t i) {
    // Same stream as the threshold sample: the diagonal counts as the
    // largest value (a patch's own light is kept in a real matrix too).
    Rng noise(seed, i);
    std::uint8_t* row = s.image.data() + i * n * channels;
    std::size_t holes = 0;
    for (std::size_t j = 0; j < n; ++j) {
      const float ln_v = i == j ? 0.0f : kernel.ln_v(points[i], points[j], noise);
      if (ln_v >= threshold) {
        ++holes;  // code 0 in every channel
        continue;
      }
      for (std::size_t c = 0; c < channels; ++c) {
        const float code = std::round(255.0f * (ln_v + shift[c] - ln_vmax + 25.0f) / 25.0f);
        row[j * channels + c] = static_cast<std::uint8_t>(std::clamp(code, 0.0f, 255.0f));
      }
    }
    holes_per_row[i] = holes;
  });
  const std::size_t holes =
      std::accumulate(holes_per_row.begin(), holes_per_row.end(), std::size_t{0});
  s.hole_fraction = static_cast<double>(holes) / (static_cast<double>(n) * static_cast<double>(n));
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

}  // namespace bounce
