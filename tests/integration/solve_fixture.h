#pragma once
// One compressed Cornell box bake made with --dump-matrices, shared by the
// tests of a suite, and `bounce solve` runs on it.
#include "cli_harness.h"

namespace bounce::itest {

class Solve : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    tmp = new TempDir();
    bake = tmp->path() / "bake";
    const RunResult r = run({"bake", scene("cornell-box"), "--voxel", "6", "--codec", "ours",
                             "--dump-matrices", "--no-pictures", "--quiet", "--out", bake.string()},
                            tmp->path());
    ASSERT_EQ(r.exit_code, 0) << r;
  }
  static void TearDownTestSuite() { delete tmp; }

  // Runs solve into its own folder; returns the patch light (n x 3 x 3:
  // irradiance, first hit, indirect).
  NpyArray<float> solve(const std::string& name, std::vector<std::string> extra,
                        json* summary = nullptr) {
    const fs::path out = tmp->path() / name;
    std::vector<std::string> args{"solve", bake.string(), "--out", out.string(), "--json"};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult r = run(args, tmp->path(), 120.0);
    EXPECT_EQ(r.exit_code, 0) << r;
    if (summary) *summary = parse_json(r.out);
    return read_npy_f32(out / "patch_light.npy");
  }

  static inline TempDir* tmp = nullptr;
  static inline fs::path bake;
};

}  // namespace bounce::itest
