// Progress contract (as Open Image Denoise tests it): fractions stay in [0,1],
// never go back, end at exactly 1, and a callback returning false cancels.
#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "base/error.h"
#include "base/progress.h"

namespace bounce {

TEST(Progress, MonotoneWithinUnitIntervalAndEndsAtOne) {
  std::vector<double> seen;
  Progress p([&](const std::string&, double f) {
    seen.push_back(f);
    return true;
  });
  p.begin_stage("work", 1000);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&] {
      for (int k = 0; k < 250; ++k) p.advance();
    });
  for (auto& t : threads) t.join();
  p.end_stage();
  ASSERT_GE(seen.size(), 2u);
  EXPECT_EQ(seen.front(), 0.0);
  EXPECT_EQ(seen.back(), 1.0);
  for (std::size_t k = 1; k < seen.size(); ++k) {
    EXPECT_GE(seen[k], seen[k - 1]);
    EXPECT_LE(seen[k], 1.0);
  }
}

TEST(Progress, CallbackReturningFalseCancels) {
  Progress p([](const std::string&, double f) { return f < 0.5; });
  p.begin_stage("work", 10);
  // Like a parallel loop: poll should_stop(), never throw inside.
  int done = 0;
  for (int k = 0; k < 10 && !p.should_stop(); ++k) {
    p.advance();
    ++done;
  }
  EXPECT_EQ(done, 5);  // the report at 50% said stop
  EXPECT_TRUE(p.should_stop());
  EXPECT_THROW(p.check(), Cancelled);
}

TEST(Progress, RequestStopMakesTheNextPollThrow) {
  Progress p;
  p.begin_stage("work", 10);
  p.request_stop();
  EXPECT_THROW(p.check(), Cancelled);
  EXPECT_THROW(p.begin_stage("next", 1), Cancelled);
}

}  // namespace bounce
