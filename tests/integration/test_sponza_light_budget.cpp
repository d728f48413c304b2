// Dabrovic Sponza (the shared data beside the repository; its licence allows
// tests but not copies in the repository), open to the sky: the suns of the
// evaluation lights reach its floor, and the compressed matrix's light error
// on the worst evaluation light is held to the budget, recomputed here from
// the bake's files alone.
#include "cli_harness.h"
#include "light_error_check.h"

namespace bounce::itest {
namespace {

const fs::path kSponza = fs::path(BOUNCE_SHARED_DATA_DIR) / "dabrovic-sponza" / "sponza.obj";

// At ~1000 patches (a small test) the matrix is less smooth than at 4096 and
// the default size limit of 1/8 of dense is not enough for 2% on the worst
// light (docs/benchmarks.md): the test allows 1/4.
TEST(SponzaLightBudget, BudgetHoldsOnTheWorstEvaluationLight) {
  if (!fs::exists(kSponza))
    GTEST_SKIP() << kSponza << " is not there (shared data not beside the repository)";
  TempDir tmp;
  const fs::path out = tmp / "bake";
  const RunResult r = run({"bake", kSponza.string(), "--patches-total", "1024", "--codec", "ours",
                           "--bounces", "2", "--final-gather-rays", "0", "--size-limit", "0.25",
                           "--dump-matrices", "--no-pictures", "--quiet", "--out", out.string()},
                          tmp.path(), 600.0);
  ASSERT_EQ(r.exit_code, 0) << r;
  const json m = read_manifest(out);
  const json& c = m["compression"];
  const json& li = c["errors"]["indirect_light"];
  // The scene's default light, four point lights and suns through the open
  // roof: more lights than a closed scene has.
  EXPECT_GT(li["lights"].get<std::size_t>(), 5u) << li;
  ASSERT_TRUE(c["error_budget_met"].get<bool>()) << c["error_budget_outcome"];
  EXPECT_LE(li["rel_rms_max"].get<double>(), c["error_budget"].get<double>());
  EXPECT_LE(c["sizes"]["stored_bytes"].get<std::size_t>(),
            c["size_limit_bytes"].get<std::size_t>());
  // The same figure from T.npy, the decoded T.dds and the light vectors.
  const RecomputedLightError e = recompute_light_error_of_bake(out, m);
  EXPECT_EQ(e.lights, li["lights"].get<std::size_t>());
  EXPECT_NEAR(e.max, li["rel_rms_max"].get<double>(), 1e-3 * e.max);
  EXPECT_LE(e.max, c["error_budget"].get<double>() * (1.0 + 1e-3));
}

}  // namespace
}  // namespace bounce::itest
