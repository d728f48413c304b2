// Spot cells: the rays landing in one cell add up, the cell keeps the
// earliest ray's landing point, and neither depends on the order rays are
// added in or on how the threads' cells are merged: checked against sums
// and minima computed over the rays directly.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <tuple>
#include <vector>

#include "runtime/gather_spots.h"

namespace bounce {

namespace {

struct Ray {
  SurfaceCellKey key;
  SpotCell cell;
};

using Flat = std::map<std::tuple<int, int, int, int, unsigned>,
                      std::tuple<std::uint64_t, std::uint64_t, float>>;

Flat flatten(const SpotCells& cells) {
  Flat out;
  cells.for_each([&](const SurfaceCellKey& k, const SpotCell& c) {
    const auto [it, added] =
        out.try_emplace({k.sample, k.x, k.y, k.z, k.triangle}, c.rays, c.first, c.position.x);
    EXPECT_TRUE(added) << "a cell listed twice";
  });
  return out;
}

}  // namespace

TEST(SpotCells, RaysAddUpAndTheEarliestRayStaysWhateverTheOrder) {
  std::mt19937 rng(3);
  std::vector<Ray> rays;
  for (std::uint64_t r = 0; r < 4000; ++r) {
    const SurfaceCellKey key{
        static_cast<std::int32_t>(rng() % 40), static_cast<std::int32_t>(rng() % 2),
        static_cast<std::int32_t>(rng() % 2), 0, static_cast<std::uint32_t>(rng() % 3)};
    rays.push_back({key, SpotCell{1, r, glm::vec3(static_cast<float>(r)), glm::vec3(0.0f)}});
  }
  // Expected: per key, the count and the smallest ray index.
  Flat expected;
  for (const Ray& r : rays) {
    auto& [count, first, x] =
        expected
            .try_emplace({r.key.sample, r.key.x, r.key.y, r.key.z, r.key.triangle}, 0, r.cell.first,
                         r.cell.position.x)
            .first->second;
    ++count;
    if (r.cell.first < first) first = r.cell.first, x = r.cell.position.x;
  }
  SpotCells in_order;
  for (const Ray& r : rays) in_order.add(r.key, r.cell);
  EXPECT_EQ(flatten(in_order), expected);
  EXPECT_EQ(in_order.size(), expected.size());
  // Shuffled, split between two "threads", merged.
  std::shuffle(rays.begin(), rays.end(), rng);
  SpotCells a, b;
  for (std::size_t k = 0; k < rays.size(); ++k) (k % 3 ? a : b).add(rays[k].key, rays[k].cell);
  SpotCells merged;
  merged.merge(b);
  merged.merge(a);
  EXPECT_EQ(flatten(merged), expected);
  EXPECT_EQ(merged.size(), expected.size());
}

}  // namespace bounce
