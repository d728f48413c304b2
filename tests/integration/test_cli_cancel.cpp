// Ctrl-C (SIGINT) or SIGTERM during a long bake: exit code 130 within a few
// seconds, and neither the bake folder nor a hidden partial folder remains.
#include <csignal>

#include "cli_harness.h"

namespace bounce::itest {
namespace {

class BakeCancel : public ::testing::TestWithParam<int> {};

TEST_P(BakeCancel, SignalMidBakeExits130AndLeavesNothing) {
  const int signal = GetParam();
  TempDir tmp;
  const fs::path out = tmp / "X";
  RunOptions options;
  options.cwd = tmp.path();
  // The bunny at --voxel 14 bakes for well over ten seconds on two cores.
  Child child({"bake", scene("cornell-bunny"), "--voxel", "14", "--out", out.string()}, options);
  // The signal goes once the bake says it started ("Baking ... into ..."),
  // which it prints after installing its handlers: a fixed wait let the
  // signal arrive before them on a loaded machine (default action, exit 143).
  while (child.running() && child.seconds_since_start() < 60.0 &&
         !contains(child.err_so_far(), "Baking "))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ASSERT_TRUE(child.running()) << "the bake ended before it could be cancelled:\n"
                               << child.wait(std::chrono::seconds(1));
  const auto sent = Clock::now();
  child.send(signal);
  const RunResult r = child.wait(std::chrono::seconds(30));
  const double to_exit = std::chrono::duration<double>(Clock::now() - sent).count();
  EXPECT_EQ(r.exit_code, 130) << r;
  EXPECT_LT(to_exit, 5.0) << "took " << to_exit << " s to stop after the signal";
  EXPECT_TRUE(contains(r.err, "cancelled")) << r;
  EXPECT_FALSE(fs::exists(out)) << "a cancelled bake left " << out;
  EXPECT_TRUE(hidden_leftovers(out).empty())
      << "hidden partial folders left: " << testing::PrintToString(hidden_leftovers(out));
  EXPECT_EQ(entries(tmp.path()), std::vector<std::string>{})
      << "the cancelled bake left files in its working folder";
}

INSTANTIATE_TEST_SUITE_P(Signals, BakeCancel, ::testing::Values(SIGINT, SIGTERM),
                         [](const ::testing::TestParamInfo<int>& p) {
                           return p.param == SIGINT ? std::string("SIGINT")
                                                    : std::string("SIGTERM");
                         });

}  // namespace
}  // namespace bounce::itest
