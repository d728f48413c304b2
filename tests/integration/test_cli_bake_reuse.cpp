// `bounce bake SCENE --out DIR` when DIR already holds a complete bake with
// the same content key (core/bake/bake_key.h): reused in seconds, exit 0,
// nothing rewritten; --force bakes again; another setting or a changed scene
// file bakes again; a corrupt folder is baked again with one warning that
// names the file, never a crash.
#include "cli_harness.h"

namespace bounce::itest {
namespace {

const std::vector<std::string> kSmall = {"--voxel",        "3",  "--bounces",           "2",
                                         "--closure-rays", "32", "--final-gather-rays", "16",
                                         "--no-pictures"};

std::vector<std::string> bake_args(const std::string& scene_dir, const fs::path& out,
                                   std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"bake", scene_dir, "--out", out.string()};
  args.insert(args.end(), kSmall.begin(), kSmall.end());
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

fs::file_time_type manifest_time(const fs::path& bake) {
  return fs::last_write_time(bake / "manifest.json");
}

TEST(BakeReuse, SameSceneAndSettingsReuseTheFolderForceBakesAgain) {
  TempDir tmp;
  const fs::path out = tmp / "box";
  const RunResult first = run(bake_args(scene("cornell-box"), out), tmp.path(), 120);
  ASSERT_EQ(first.exit_code, 0) << first;
  const json manifest = read_manifest(out);
  ASSERT_TRUE(manifest.contains("key")) << "the manifest records the content key";
  EXPECT_EQ(manifest["key"].get<std::string>().size(), 16u);
  const auto written = manifest_time(out);

  // A copy of the scene folder elsewhere: the same contents, the same key.
  const fs::path copy = tmp / "elsewhere" / "my-box";
  fs::create_directories(copy.parent_path());
  fs::copy(kScenes / "cornell-box", copy, fs::copy_options::recursive);
  const RunResult again = run(bake_args(copy.string(), out), tmp.path(), 60);
  EXPECT_EQ(again.exit_code, 0) << again;
  EXPECT_TRUE(contains(again.err, "is up to date")) << again;
  EXPECT_FALSE(contains(again.err, "Baking ")) << again;
  EXPECT_EQ(manifest_time(out), written) << "a reused folder is not rewritten";
  EXPECT_LT(again.seconds, 10.0) << again;

  const RunResult forced = run(bake_args(copy.string(), out, {"--force"}), tmp.path(), 120);
  EXPECT_EQ(forced.exit_code, 0) << forced;
  EXPECT_TRUE(contains(forced.err, "Baking ")) << forced;
  EXPECT_EQ(read_manifest(out)["key"], manifest["key"]);
}

TEST(BakeReuse, AnotherSettingOrSceneByteBakesAgain) {
  TempDir tmp;
  const fs::path out = tmp / "box";
  const fs::path copy = tmp / "scene";
  fs::copy(kScenes / "cornell-box", copy, fs::copy_options::recursive);
  ASSERT_EQ(run(bake_args(copy.string(), out), tmp.path(), 120).exit_code, 0);
  const std::string key = read_manifest(out)["key"];

  const RunResult seed = run(bake_args(copy.string(), out, {"--seed", "2"}), tmp.path(), 120);
  EXPECT_EQ(seed.exit_code, 0) << seed;
  EXPECT_TRUE(contains(seed.err, "Baking ")) << seed;
  const std::string seed_key = read_manifest(out)["key"];
  EXPECT_NE(seed_key, key);

  // One byte of the mesh file's leading comment.
  std::string obj = read_text(copy / "CornellBox-Original.obj");
  obj[2] = obj[2] == 'x' ? 'y' : 'x';
  write_text(copy / "CornellBox-Original.obj", obj);
  const RunResult edited = run(bake_args(copy.string(), out, {"--seed", "2"}), tmp.path(), 120);
  EXPECT_EQ(edited.exit_code, 0) << edited;
  EXPECT_TRUE(contains(edited.err, "Baking ")) << edited;
  EXPECT_NE(read_manifest(out)["key"].get<std::string>(), seed_key);
}

TEST(BakeReuse, ACorruptFolderIsBakedAgainAndSaysWhy) {
  TempDir tmp;
  const fs::path out = tmp / "box";
  ASSERT_EQ(run(bake_args(scene("cornell-box"), out), tmp.path(), 120).exit_code, 0);
  fs::resize_file(out / "patches.npy", 64);
  const RunResult truncated = run(bake_args(scene("cornell-box"), out), tmp.path(), 120);
  EXPECT_EQ(truncated.exit_code, 0) << truncated;
  EXPECT_TRUE(contains(truncated.err, "not reused, baking again")) << truncated;
  EXPECT_TRUE(contains(truncated.err, "patches.npy")) << truncated;
  EXPECT_TRUE(contains(truncated.err, "Baking ")) << truncated;

  write_text(out / "manifest.json", "{\"key\": 12, \"files\": \"x\"");
  const RunResult garbage = run(bake_args(scene("cornell-box"), out), tmp.path(), 120);
  EXPECT_EQ(garbage.exit_code, 0) << garbage;
  EXPECT_TRUE(contains(garbage.err, "manifest.json")) << garbage;
  EXPECT_TRUE(read_manifest(out).contains("key"));
}

}  // namespace
}  // namespace bounce::itest
