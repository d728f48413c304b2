// Dabrovic Sponza (the shared data beside the repository; its licence allows
// tests but not copies in the repository): the balanced form factors of a real
// architectural scene, open to the sky, keep every row at or below its
// patch's closure, and no closure above 1.
#include "cli_harness.h"

namespace bounce::itest {
namespace {

const fs::path kSponza = fs::path(BOUNCE_SHARED_DATA_DIR) / "dabrovic-sponza" / "sun.json";

TEST(SponzaEnergy, RowsAtMostTheirClosureAndClosuresAtMostOne) {
  if (!fs::exists(kSponza))
    GTEST_SKIP() << kSponza << " is not there (shared data not beside the repository)";
  TempDir tmp;
  const fs::path out = tmp / "bake";
  const RunResult r = run({"bake", kSponza.string(), "--patches-total", "1024", "--codec", "dense",
                           "--bounces", "1", "--no-pictures", "--out", out.string()},
                          tmp.path(), 300.0);
  ASSERT_EQ(r.exit_code, 0) << r;
  const json m = read_manifest(out);
  const json& ff = m.at("checks").at("form_factors");
  // The raw quadrature had rows above 1 (396 at 4096 patches); balanced, none.
  EXPECT_EQ(ff.at("rows_above_closure").get<std::size_t>(), 0u) << ff.dump(2);
  EXPECT_LE(ff.at("row_sum_max").get<double>(), 1.0 + 1e-3) << ff.dump(2);
  EXPECT_EQ(ff.at("rows_above_one").get<std::size_t>(), 0u) << ff.dump(2);
  EXPECT_LE(ff.at("closure").at("max").get<double>(), 1.0);
  // The atrium is open to the sky: some light escapes, so closures are below 1.
  EXPECT_LT(ff.at("closure").at("mean_area_weighted").get<double>(), 0.99);
  EXPECT_GT(ff.at("closure").at("mean_area_weighted").get<double>(), 0.5);
  EXPECT_TRUE(ff.at("balance").at("converged").get<bool>()) << ff.dump(2);
  // closure.npy matches what the rows were balanced to.
  const NpyArray<float> c = read_npy_f32(out / "closure.npy");
  ASSERT_EQ(c.shape.size(), 2u);
  EXPECT_EQ(c.shape[0], m.at("counts").at("patches").get<std::size_t>());
  for (std::size_t p = 0; p < c.shape[0]; ++p) {
    EXPECT_GE(c.data[2 * p], 0.0f);
    EXPECT_LE(c.data[2 * p], 1.0f);
  }
}

}  // namespace
}  // namespace bounce::itest
