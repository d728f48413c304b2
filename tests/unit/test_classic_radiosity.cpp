// The classic per-frame iteration against the precomputed K-bounce matrix:
// sum_(h=1..K) M^h b computed two independent ways must agree.
#include <gtest/gtest.h>

#include <random>

#include "runtime/classic_radiosity.h"
#include "runtime/dense_transport.h"
#include "transport/transport.h"

namespace bounce {
namespace {

TEST(ClassicRadiosity, KIterationsEqualTheKBounceMatrix) {
  const std::size_t n = 57;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  FormFactorMatrix f;
  f.n = n;
  f.values.resize(n * n);
  for (std::size_t p = 0; p < n; ++p) {
    float sum = 0.0f;
    for (std::size_t q = 0; q < n; ++q) sum += f.values[p * n + q] = p == q ? 0.0f : u(rng);
    for (std::size_t q = 0; q < n; ++q) f.values[p * n + q] *= 0.95f / sum;
  }
  std::vector<glm::vec3> albedo(n), b(n);
  for (std::size_t p = 0; p < n; ++p) {
    albedo[p] = {0.8f * u(rng), 0.5f, 0.2f + 0.5f * u(rng)};
    b[p] = {u(rng), u(rng), u(rng)};
  }
  for (int k : {1, 3, 7}) {
    TransportSettings s;
    s.bounces = k;
    s.backend = TransportSettings::Backend::OpenBLAS;
    Diagnostics d;
    const TransportResult t = compute_transport(f, albedo, s, nullptr, d);
    std::vector<const float*> m;
    std::array<int, 3> map{};
    for (std::size_t c = 0; c < t.channels.size(); ++c) {
      m.push_back(t.channels[c].t.data());
      for (int rgb : t.channels[c].rgb) map[static_cast<std::size_t>(rgb)] = static_cast<int>(c);
    }
    std::vector<glm::vec3> expected, got;
    dense_indirect(m, n, map, b, expected);
    const ClassicRadiosity classic({f.values.begin(), f.values.end()}, albedo, k);
    classic.multiply(b, got);
    for (std::size_t p = 0; p < n; ++p)
      for (int c = 0; c < 3; ++c)
        // float32 sums of n terms over K bounces: a few K n eps relative.
        EXPECT_NEAR(got[p][c], expected[p][c], 1e-5f * (1.0f + expected[p][c])) << k;
    std::vector<glm::vec3> again;
    classic.multiply(b, again);
    EXPECT_EQ(again, got) << "a second update must give the same result";
  }
}

}  // namespace
}  // namespace bounce
