// The final gather's product over a k-th of its rows a frame
// (runtime/gather_row_budget.h): a slice sums exactly the rows of its bands,
// to the bit as the whole product does, and leaves every other row as it
// was; the k slices in turn give the whole product. The budget hands out
// the slices in turn while the sources are not exact, and every row when
// they are or when nothing has been summed yet.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "base/error.h"
#include "runtime/gather_row_budget.h"
#include "runtime/gather_row_loops.h"

namespace bounce {
namespace {

struct SyntheticRows {
  std::vector<gather_loops::PaddedLight> light;
  std::vector<std::uint64_t> first;
  std::vector<std::uint32_t> entry;
  gather_loops::CompactRows rows() const {
    return {light.data(), first.data(), entry.data(), 8, 1.0f / 256.0f};
  }
  std::size_t count() const { return first.size() - 1; }
};

// 5 bands and a part: rows of 0 to 12 entries, ray counts 1 to 255 in the
// low 8 bits, sources among 97 lights.
SyntheticRows synthetic_rows() {
  SyntheticRows r;
  for (std::size_t s = 0; s < 97; ++s)
    r.light.push_back(
        {{0.01f * static_cast<float>(s), 1.0f, 0.5f + 0.003f * static_cast<float>(s), 0.0f}});
  r.first.push_back(0);
  std::uint32_t state = 12345;
  const auto next = [&] { return state = state * 1664525u + 1013904223u; };
  for (std::size_t row = 0; row < 5 * kRowBand + 300; ++row) {
    const std::size_t n = next() % 13;
    for (std::size_t k = 0; k < n; ++k)
      r.entry.push_back(((next() % 97) << 8) | (1 + next() % 255));
    r.first.push_back(r.entry.size());
  }
  return r;
}

TEST(GatherRowBudget, ASliceSumsItsBandsExactlyAndLeavesTheOtherRows) {
  const SyntheticRows r = synthetic_rows();
  constexpr int kSlices = 3;
  for (const gather_loops::CompactLoop& loop : gather_loops::compact_loops()) {
    std::vector<glm::vec3> whole(r.count());
    gather_loops::sum_compact_rows(loop, r.rows(), r.count(), whole.data());
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<glm::vec3> sliced(r.count(), glm::vec3(nan));
    for (int s = 0; s < kSlices; ++s) {
      gather_loops::sum_compact_rows(loop, r.rows(), r.count(), sliced.data(), {s, kSlices});
      for (std::size_t row = 0; row < r.count(); ++row) {
        const bool summed = static_cast<int>(row / kRowBand % kSlices) <= s;
        if (summed)
          ASSERT_EQ(sliced[row], whole[row]) << loop.name << ", slice " << s << ", row " << row;
        else
          ASSERT_TRUE(std::isnan(sliced[row].x))
              << loop.name << ", slice " << s << " wrote row " << row;
      }
    }
  }
}

TEST(GatherRowBudget, SlicesInTurnWhileTheSourcesAreNotExactEveryRowWhenTheyAre) {
  GatherRowBudget budget(3);
  EXPECT_TRUE(budget.settled()) << "nothing summed yet, nothing lags";
  EXPECT_TRUE(budget.next(false, true).all()) << "nothing kept: every row";
  EXPECT_TRUE(budget.settled());
  for (int expected : {0, 1, 2, 0}) {
    const RowSlice rows = budget.next(false, false);
    EXPECT_EQ(rows.slice, expected);
    EXPECT_EQ(rows.slices, 3);
    EXPECT_FALSE(budget.settled());
  }
  EXPECT_TRUE(budget.next(true, false).all());
  EXPECT_TRUE(budget.settled());
  GatherRowBudget every(1);
  EXPECT_TRUE(every.next(false, false).all());
  EXPECT_TRUE(every.settled());
  EXPECT_THROW(GatherRowBudget(0), Error);
}

}  // namespace
}  // namespace bounce
