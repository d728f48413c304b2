#pragma once
// One compressed Cornell box bake made with --dump-matrices, shared by the
// tests of a suite, and `bounce solve` runs on it.
#include <functional>
#include <string>
#include <system_error>

#include "cli_harness.h"

namespace bounce::itest {

class Solve : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    tmp = new TempDir();
    bake = shared_bake();
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

 private:
  // ctest runs every test in a process of its own, so a bake per suite was a
  // bake per test (~28 of them, 10-15 s each). The bake is made once per
  // build of the CLI instead: its folder is named by the CLI's path, size and
  // modification time, made in a staging folder and renamed into place. A
  // process racing another either finds the whole folder or keeps its own
  // staged bake; no test finds half a bake. Tests only read it (damaging
  // tests work on copies).
  static fs::path shared_bake() {
    const std::string identity =
        kCli.string() + ":" + std::to_string(fs::file_size(kCli)) + ":" +
        std::to_string(fs::last_write_time(kCli).time_since_epoch().count());
    const fs::path home =
        fs::temp_directory_path() /
        ("bounce-itest-solve-bake-" + std::to_string(std::hash<std::string>{}(identity)));
    const fs::path shared = home / "bake";
    if (fs::exists(shared / "manifest.json")) return shared;
    fs::create_directories(home);
    const fs::path staged = tmp->path() / "bake";
    const RunResult r =
        run({"bake", scene("cornell-box"), "--voxel", "6", "--codec", "ours", "--dump-matrices",
             "--no-pictures", "--quiet", "--out", staged.string()},
            tmp->path());
    EXPECT_EQ(r.exit_code, 0) << r;
    if (r.exit_code != 0) return staged;
    // Renaming onto a folder another process has already put in place
    // fails; then both are whole and the staged one serves this process.
    std::error_code ec;
    fs::rename(staged, shared, ec);
    return ec ? staged : shared;
  }
};

}  // namespace bounce::itest
