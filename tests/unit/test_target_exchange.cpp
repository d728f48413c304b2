// The clustering's exchange sums, computed eight sources at a time: each
// lane must equal a scalar loop over bounded_exchange bit for bit (the
// clustering, and so every patch, depends on the exact sums), for points
// that face each other, turn away, coincide, and for fewer than eight sources.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "patches/target_exchange.h"

namespace bounce {

namespace {

std::vector<SurfacePoint> random_points(std::mt19937& rng, std::size_t count) {
  std::uniform_real_distribution<float> coord(-2.0f, 2.0f), area(0.001f, 0.2f);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  std::vector<SurfacePoint> points;
  for (std::size_t i = 0; i < count; ++i) {
    glm::vec3 n(normal(rng), normal(rng), normal(rng));
    n = glm::normalize(n);
    points.push_back({{coord(rng), coord(rng), coord(rng)}, n, area(rng)});
  }
  return points;
}

float scalar_sum(const SurfacePoint& a, const std::vector<SurfacePoint>& target) {
  float sum = 0.0f;
  for (const SurfacePoint& b : target) sum += bounded_exchange(a, b);
  return sum;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST(TargetExchange, EachLaneEqualsTheScalarSumToTheLastBit) {
  std::mt19937 rng(7);
  std::vector<std::vector<SurfacePoint>> targets;
  TargetPoints points;
  for (std::size_t t = 0; t < 40; ++t) {
    targets.push_back(random_points(rng, t % 7));  // some targets empty
    points.add_target(targets.back());
  }
  std::vector<SurfacePoint> sources = random_points(rng, 8);
  sources[3] = targets[5][1];  // a source on a target point: r2 = 0 counts nothing
  for (std::size_t count : {std::size_t{8}, std::size_t{5}, std::size_t{1}}) {
    std::vector<float> sums(points.targets() * kExchangeLanes, -1.0f);
    exchange_with_targets(sources.data(), count, points, sums.data());
    std::size_t positive = 0;
    for (std::size_t t = 0; t < targets.size(); ++t) {
      for (std::size_t l = 0; l < kExchangeLanes; ++l) {
        const float got = sums[t * kExchangeLanes + l];
        const float want = l < count ? scalar_sum(sources[l], targets[t]) : 0.0f;
        EXPECT_TRUE(same_bits(got, want))
            << "target " << t << " lane " << l << ": " << got << " vs " << want;
        positive += got > 0.0f;
      }
    }
    EXPECT_GT(positive, count * 5) << "too few facing pairs to test anything";
  }
}

TEST(TargetExchange, PointsThatTurnAwayExchangeNothing) {
  TargetPoints points;
  // Facing the source (normal -z, above it) and turned away (normal +z).
  points.add_target({{{0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, -1.0f}, 0.1f}});
  points.add_target({{{0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 1.0f}, 0.1f}});
  const SurfacePoint source{{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}, 0.1f};
  std::vector<float> sums(2 * kExchangeLanes);
  exchange_with_targets(&source, 1, points, sums.data());
  // Head-on at distance 1: A A / (pi + A).
  EXPECT_FLOAT_EQ(sums[0], 0.1f * 0.1f / (std::numbers::pi_v<float> + 0.1f));
  EXPECT_EQ(sums[kExchangeLanes], 0.0f);
}

}  // namespace bounce
